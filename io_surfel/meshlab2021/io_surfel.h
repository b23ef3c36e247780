// MeshLab 2021.05+ IO plugin (IOPlugin; built against 2022.02 and 2025.07) for `.surfel` files
// (docs/surfel_format.md). A thin adapter: what every host shares is in ../surfel_layer_io.h.
#ifndef GAUSSPHERE_IO_SURFEL_IO_SURFEL_H
#define GAUSSPHERE_IO_SURFEL_IO_SURFEL_H

#include <common/plugins/interfaces/io_plugin.h>

class SurfelIOPlugin : public QObject, public IOPlugin
{
	Q_OBJECT
	MESHLAB_PLUGIN_IID_EXPORTER(IO_PLUGIN_IID)
	Q_INTERFACES(IOPlugin)

public:
	QString pluginName() const override;
	std::list<FileFormat> importFormats() const override;
	std::list<FileFormat> exportFormats() const override;
	void exportMaskCapability(const QString& format, int& capability, int& defaultBits) const override;

	void open(const QString& format, const QString& fileName, MeshModel& m, int& mask,
	          const RichParameterList& par, vcg::CallBackPos* cb = nullptr) override;
	void save(const QString& format, const QString& fileName, MeshModel& m, const int mask,
	          const RichParameterList& par, vcg::CallBackPos* cb = nullptr) override;
};

#endif
