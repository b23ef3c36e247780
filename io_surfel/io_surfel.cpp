#include "io_surfel.h"

#include "surfel_file.h"
#include "surfel_records_mesh.h"

#include <QFile>

#include <cstdio>

using surfel_io::SurfelRecord;

namespace {

// Everything a .surfel file stores; saving writes all of it whatever the mask asks.
constexpr int kSurfelComponents = vcg::tri::io::Mask::IOM_VERTCOORD |
                                  vcg::tri::io::Mask::IOM_VERTNORMAL |
                                  vcg::tri::io::Mask::IOM_VERTRADIUS |
                                  vcg::tri::io::Mask::IOM_VERTQUALITY |
                                  vcg::tri::io::Mask::IOM_VERTCOLOR;

std::string localPath(const QString& fileName)
{
	return QFile::encodeName(fileName).toStdString();
}

}  // namespace

// MeshLab 2020.09's meshlabserver prints neither errorMsg() nor the log of a failed load or
// save (only "Failed loading of FILE" / "Failed saving"), so the reason also goes to stderr;
// the GUI shows errorMsg() in its dialog, and the log when it has one.
bool SurfelIOPlugin::fail(const char* action, const QString& fileName, const std::string& reason)
{
	const std::string line = std::string("IOSurfel: cannot ") + action + " '" +
	                         surfel_io::printableText(localPath(fileName), 100, true) + "': " + reason;
	errorMessage = QString::fromStdString(line);
	std::fprintf(stderr, "%s\n", line.c_str());
	Log(GLLogStream::WARNING, line);
	return false;
}

QString SurfelIOPlugin::pluginName() const
{
	return "IOSurfel";
}

QList<MeshIOInterface::Format> SurfelIOPlugin::importFormats() const
{
	return {Format("Gaussian sphere surfels", tr("SURFEL"))};
}

QList<MeshIOInterface::Format> SurfelIOPlugin::exportFormats() const
{
	return importFormats();
}

void SurfelIOPlugin::GetExportMaskCapability(QString& /*format*/, int& capability,
                                             int& defaultBits) const
{
	capability = defaultBits = kSurfelComponents;
}

bool SurfelIOPlugin::open(const QString& /*format*/, const QString& fileName, MeshModel& m,
                          int& mask, const RichParameterList& /*par*/, vcg::CallBackPos* cb,
                          QWidget* /*parent*/)
{
	// The GUI takes any message left after a successful load for a warning, and clears it only
	// after loads: one left by a failed save would show then.
	clearErrorString();
	if (cb != nullptr) (*cb)(0, "Loading surfels...");
	std::vector<SurfelRecord> surfels;
	std::string error;
	if (!surfel_io::readSurfelFile(localPath(fileName), surfels, error))
		return fail("load", fileName, error);

	// The normal flag also keeps MeshLab from recomputing normals of this face-less layer.
	mask = kSurfelComponents;
	m.Enable(mask);
	surfel_io::addRecordsToMesh(surfels, m.cm);
	vcg::tri::UpdateBounding<CMeshO>::Box(m.cm);
	if (!surfels.empty() && !surfel_io::hasEllipseFrames(surfels))
		Log("%s: every ellipse axis is zero, the layer gets no ellipse attributes",
		    qUtf8Printable(fileName));
	if (cb != nullptr) (*cb)(100, "Done");
	return true;
}

bool SurfelIOPlugin::save(const QString& /*format*/, const QString& fileName, MeshModel& m,
                          const int /*mask*/, const RichParameterList& /*par*/,
                          vcg::CallBackPos* cb, QWidget* /*parent*/)
{
	clearErrorString();
	if (cb != nullptr) (*cb)(0, "Saving surfels...");
	const std::vector<SurfelRecord> surfels = surfel_io::recordsFromMesh(m.cm);
	std::string error;
	if (!surfel_io::writeSurfelFile(localPath(fileName), surfels, error))
		return fail("save", fileName, error);
	if (!surfels.empty() && !surfel_io::hasEllipseFrames(surfels))
		Log("%s: the layer has no ellipse frames, written with zero axes",
		    qUtf8Printable(fileName));
	if (cb != nullptr) (*cb)(100, "Done");
	return true;
}

MESHLAB_PLUGIN_NAME_EXPORTER(SurfelIOPlugin)
