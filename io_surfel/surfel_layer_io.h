// The .surfel IO plugin's MeshLab glue that is the same for every host (2020.09, 2022.02,
// 2025.07): the format, the components it stores, and loading and saving one layer through
// surfel_file (the codec) and surfel_records_mesh.h. It neither logs nor throws: it returns an
// error line and a note for the log, and each host's adapter (meshlab2020/, meshlab2021/)
// reports them its host's way.
#ifndef GAUSSPHERE_IO_SURFEL_SURFEL_LAYER_IO_H
#define GAUSSPHERE_IO_SURFEL_SURFEL_LAYER_IO_H

#include <QString>

#include <meshlab_glue/meshlab_document.h>

namespace surfel_layer_io {

QString PluginName();
QString FormatDescription();
QString FormatExtension();  ///< "SURFEL"
bool IsSurfelFormat(const QString &format);

/// Everything a .surfel file stores (vcg::tri::io::Mask bits); saving writes all of it whatever
/// the mask asks.
int ComponentMask();

struct IoOutcome
{
    /// Empty on success, else one printable line "IOSurfel: cannot load|save '<path>': <reason>".
    QString error;
    /// Empty, or a line for the log about what the layer lacks (no ellipse frames).
    QString note;
};

/// Reads `fileName` into the empty layer `m` and sets `mask` to the components it filled.
IoOutcome OpenLayer(const QString &fileName, MeshModel &m, int &mask, vcg::CallBackPos *cb);

/// Writes the live vertices of `m` to `fileName`.
IoOutcome SaveLayer(const QString &fileName, MeshModel &m, vcg::CallBackPos *cb);

} // namespace surfel_layer_io

#endif
