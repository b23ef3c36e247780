// MeshLab 2020.09 IO plugin (MeshIOInterface) for `.surfel` files (docs/surfel_format.md): the
// resampled surfel layers with their radius, quality, colour and ellipse attributes, which PLY
// loses. A thin adapter: what every host shares is in ../surfel_layer_io.h.
#ifndef GAUSSPHERE_IO_SURFEL_IO_SURFEL_H
#define GAUSSPHERE_IO_SURFEL_IO_SURFEL_H

#include <common/interfaces.h>

class SurfelIOPlugin : public QObject, public MeshIOInterface
{
	Q_OBJECT
	MESHLAB_PLUGIN_IID_EXPORTER(MESH_IO_INTERFACE_IID)
	Q_INTERFACES(MeshIOInterface)

public:
	QString pluginName() const override;
	QList<Format> importFormats() const override;
	QList<Format> exportFormats() const override;
	void GetExportMaskCapability(QString& format, int& capability, int& defaultBits) const override;

	bool open(const QString& format, const QString& fileName, MeshModel& m, int& mask,
	          const RichParameterList& par, vcg::CallBackPos* cb = nullptr,
	          QWidget* parent = nullptr) override;
	bool save(const QString& format, const QString& fileName, MeshModel& m, const int mask,
	          const RichParameterList& par, vcg::CallBackPos* cb = nullptr,
	          QWidget* parent = nullptr) override;

private:
	// Reports an outcome of ../surfel_layer_io.h: its error (returns false) or its note.
	bool report(const QString& error, const QString& note);
};

#endif
