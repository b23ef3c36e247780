#include "io_surfel.h"

#include <common/mlexception.h>

#include "../surfel_layer_io.h"

namespace sl = surfel_layer_io;

namespace {

// Throws the error line; the note goes to the log the host gives the plugin.
void report(const IOPlugin& plugin, const sl::IoOutcome& outcome)
{
	if (!outcome.error.isEmpty()) throw MLException(outcome.error);
	if (!outcome.note.isEmpty()) plugin.log(outcome.note.toStdString());
}

}  // namespace

QString SurfelIOPlugin::pluginName() const
{
	return sl::PluginName();
}

std::list<FileFormat> SurfelIOPlugin::importFormats() const
{
	return {FileFormat(sl::FormatDescription(), sl::FormatExtension())};
}

std::list<FileFormat> SurfelIOPlugin::exportFormats() const
{
	return importFormats();
}

void SurfelIOPlugin::exportMaskCapability(const QString& format, int& capability, int& defaultBits) const
{
	if (!sl::IsSurfelFormat(format)) wrongSaveFormat(format);
	capability = defaultBits = sl::ComponentMask();
}

void SurfelIOPlugin::open(const QString& format, const QString& fileName, MeshModel& m, int& mask,
                          const RichParameterList& /*par*/, vcg::CallBackPos* cb)
{
	if (!sl::IsSurfelFormat(format)) wrongOpenFormat(format);
	report(*this, sl::OpenLayer(fileName, m, mask, cb));
}

void SurfelIOPlugin::save(const QString& format, const QString& fileName, MeshModel& m, const int /*mask*/,
                          const RichParameterList& /*par*/, vcg::CallBackPos* cb)
{
	if (!sl::IsSurfelFormat(format)) wrongSaveFormat(format);
	report(*this, sl::SaveLayer(fileName, m, cb));
}

MESHLAB_PLUGIN_NAME_EXPORTER(SurfelIOPlugin)
