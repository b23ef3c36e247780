#include "surfel_layer_io.h"

#include <QFile>

#include <wrap/io_trimesh/io_mask.h>

#include "surfel_file.h"
#include "surfel_records_mesh.h"

namespace surfel_layer_io {
namespace {

std::string LocalPath(const QString &fileName) { return QFile::encodeName(fileName).toStdString(); }

IoOutcome Failure(const char *action, const QString &fileName, const std::string &reason)
{
    IoOutcome outcome;
    outcome.error = QString::fromStdString(std::string("IOSurfel: cannot ") + action + " '" +
                                           surfel_io::printableText(LocalPath(fileName), 100, true) + "': " + reason);
    return outcome;
}

void Progress(vcg::CallBackPos *cb, int percent, const char *text)
{
    if (cb != nullptr) (*cb)(percent, text);
}

} // namespace

QString PluginName() { return "IOSurfel"; }

QString FormatDescription() { return "Gaussian sphere surfels"; }

QString FormatExtension() { return "SURFEL"; }

bool IsSurfelFormat(const QString &format) { return format.compare(FormatExtension(), Qt::CaseInsensitive) == 0; }

int ComponentMask()
{
    using vcg::tri::io::Mask;
    return Mask::IOM_VERTCOORD | Mask::IOM_VERTNORMAL | Mask::IOM_VERTRADIUS | Mask::IOM_VERTQUALITY |
           Mask::IOM_VERTCOLOR;
}

IoOutcome OpenLayer(const QString &fileName, MeshModel &m, int &mask, vcg::CallBackPos *cb)
{
    Progress(cb, 0, "Loading surfels...");
    std::vector<surfel_io::SurfelRecord> surfels;
    std::string error;
    if (!surfel_io::readSurfelFile(LocalPath(fileName), surfels, error)) return Failure("load", fileName, error);

    // The normal flag also keeps MeshLab from recomputing normals of this face-less layer.
    // Positions and normals are always allocated: the optional components are the others.
    mask = ComponentMask();
    m.updateDataMask(MeshModel::MM_VERTCOLOR | MeshModel::MM_VERTRADIUS | MeshModel::MM_VERTQUALITY);
    surfel_io::addRecordsToMesh(surfels, m.cm);
    vcg::tri::UpdateBounding<CMeshO>::Box(m.cm);
    IoOutcome outcome;
    if (!surfels.empty() && !surfel_io::hasEllipseFrames(surfels))
        outcome.note = fileName + ": every ellipse axis is zero, the layer gets no ellipse attributes";
    Progress(cb, 100, "Done");
    return outcome;
}

IoOutcome SaveLayer(const QString &fileName, MeshModel &m, vcg::CallBackPos *cb)
{
    Progress(cb, 0, "Saving surfels...");
    const std::vector<surfel_io::SurfelRecord> surfels = surfel_io::recordsFromMesh(m.cm);
    std::string error;
    if (!surfel_io::writeSurfelFile(LocalPath(fileName), surfels, error)) return Failure("save", fileName, error);
    IoOutcome outcome;
    if (!surfels.empty() && !surfel_io::hasEllipseFrames(surfels))
        outcome.note = fileName + ": the layer has no ellipse frames, written with zero axes";
    Progress(cb, 100, "Done");
    return outcome;
}

} // namespace surfel_layer_io
