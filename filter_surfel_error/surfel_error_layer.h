// The Surfel Approximation Error filter's MeshLab glue that is the same for every host
// (2020.09, 2022.02, 2025.07): the name and help, the default layers and the parameters after
// them, and the measurement of one layer against another. It neither logs nor throws: it
// returns the log lines and an error text, and each host's adapter (meshlab2020/,
// meshlab2021/) reports them its host's way. The metric is vcg_ext/surfel_error/surfel_error.h.
#ifndef FILTER_SURFEL_ERROR_SURFEL_ERROR_LAYER_H
#define FILTER_SURFEL_ERROR_SURFEL_ERROR_LAYER_H

#include <vector>

#include <QString>

#include <meshlab_glue/meshlab_document.h>

namespace surfel_error_filter {

QString PluginName();
QString FilterName();
QString FilterInfo();

/// The two layer parameters, built by each adapter with its host's RichMesh.
struct LayerParameter
{
    const char *name;
    const char *label;
    const char *help;
};
extern const LayerParameter kOriginalLayer;
extern const LayerParameter kSimplifiedLayer;

/// Ids of the layers the dialog proposes (-1: none): the layer carrying SurfelIndex (a
/// resampling's input) as the original, the current layer or else another one as the simplified.
struct LayerChoice
{
    int original = -1;
    int simplified = -1;
};
LayerChoice DefaultLayers(const MeshDocument &md);

/// The parameters after the two layers, in dialog order.
void AddOptionParameters(RichParameterList &par);

/// Every parameter in dialog order; `richMesh(const LayerParameter&, int id)` returns the host's
/// RichMesh for a layer parameter and its default layer.
template <class RichMeshMaker>
void AddParameters(const MeshDocument &md, RichParameterList &par, RichMeshMaker richMesh)
{
    const LayerChoice layers = DefaultLayers(md);
    par.addParam(richMesh(kOriginalLayer, layers.original));
    par.addParam(richMesh(kSimplifiedLayer, layers.simplified));
    AddOptionParameters(par);
}

struct LogLine
{
    bool warning;
    QString text;
};

struct MeasureOutcome
{
    QString error;             ///< empty on success
    std::vector<LogLine> log;  ///< to log before the error, if any
};

/// Measures `simplified` against `original` (null: not chosen), writes the distances into the
/// original's vertex quality (and colour when asked).
MeasureOutcome Measure(MeshModel *original, MeshModel *simplified, const RichParameterList &par,
                       vcg::CallBackPos *cb);

} // namespace surfel_error_filter

#endif
