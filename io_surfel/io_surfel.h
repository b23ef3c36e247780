// MeshLab IO plugin for `.surfel` files (docs/surfel_format.md): the resampled surfel
// layers with their radius, quality, colour and ellipse attributes, which PLY loses.
#ifndef GAUSSPHERE_IO_SURFEL_IO_SURFEL_H
#define GAUSSPHERE_IO_SURFEL_IO_SURFEL_H

#include <common/interfaces.h>

#include <string>

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
	// Reports `reason` (surfel_file's one-line reason) for `action` ("load", "save") on
	// `fileName` and returns false.
	bool fail(const char* action, const QString& fileName, const std::string& reason);
};

#endif
