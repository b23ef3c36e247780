#include "io_surfel.h"

#include "../surfel_layer_io.h"

#include <cstdio>

namespace sl = surfel_layer_io;

// MeshLab 2020.09's meshlabserver prints neither errorMsg() nor the log of a failed load or
// save (only "Failed loading of FILE" / "Failed saving"), so the reason also goes to stderr;
// the GUI shows errorMsg() in its dialog, and the log when it has one.
bool SurfelIOPlugin::report(const QString& error, const QString& note)
{
	if (error.isEmpty()) {
		if (!note.isEmpty()) Log(qUtf8Printable(note));
		return true;
	}
	errorMessage = error;
	std::fprintf(stderr, "%s\n", qUtf8Printable(error));
	Log(GLLogStream::WARNING, error.toStdString());
	return false;
}

QString SurfelIOPlugin::pluginName() const
{
	return sl::PluginName();
}

QList<MeshIOInterface::Format> SurfelIOPlugin::importFormats() const
{
	return {Format(sl::FormatDescription(), sl::FormatExtension())};
}

QList<MeshIOInterface::Format> SurfelIOPlugin::exportFormats() const
{
	return importFormats();
}

void SurfelIOPlugin::GetExportMaskCapability(QString& /*format*/, int& capability,
                                             int& defaultBits) const
{
	capability = defaultBits = sl::ComponentMask();
}

bool SurfelIOPlugin::open(const QString& /*format*/, const QString& fileName, MeshModel& m,
                          int& mask, const RichParameterList& /*par*/, vcg::CallBackPos* cb,
                          QWidget* /*parent*/)
{
	// The GUI takes any message left after a successful load for a warning, and clears it only
	// after loads: one left by a failed save would show then.
	clearErrorString();
	const sl::IoOutcome outcome = sl::OpenLayer(fileName, m, mask, cb);
	return report(outcome.error, outcome.note);
}

bool SurfelIOPlugin::save(const QString& /*format*/, const QString& fileName, MeshModel& m,
                          const int /*mask*/, const RichParameterList& /*par*/,
                          vcg::CallBackPos* cb, QWidget* /*parent*/)
{
	clearErrorString();
	const sl::IoOutcome outcome = sl::SaveLayer(fileName, m, cb);
	return report(outcome.error, outcome.note);
}

MESHLAB_PLUGIN_NAME_EXPORTER(SurfelIOPlugin)
