// The filter's MeshLab glue that is the same for every host (2020.09, 2022.02, 2025.07): the
// name and help, the dialog's parameters from the one table (resampling_params.h), and the run
// on the current layer that adds the resampled layer. It neither logs nor throws: it returns
// the log lines and an error text, and each host's adapter (meshlab2020/, meshlab2021/)
// reports them its host's way.
#ifndef FILTER_GAUSSPHERE_RESAMPLE_LAYER_H
#define FILTER_GAUSSPHERE_RESAMPLE_LAYER_H

#include <string>
#include <vector>

#include <QString>

#include <meshlab_glue/meshlab_document.h>
#include <vcg_ext/gaussphere/resampling_params.h>

#include "resampling_log.h"

namespace gaussphere_filter {

using vcg::gaussphere::ResamplingFilter;

/// The plugin's filters by action id: 0 the feature-sensitive one, 1 the one for reconstruction.
inline bool IsFilter(int id) { return id == 0 || id == 1; }
inline ResamplingFilter FilterOf(int id)
{
    return id == 1 ? ResamplingFilter::ForReconstruction : ResamplingFilter::FeatureSensitive;
}

QString PluginName();
QString FilterName(ResamplingFilter filter);
QString FilterInfo(ResamplingFilter filter);

/// The table's parameters `filter`'s dialog shows (InDialog), in dialog order; the others keep
/// their defaults.
void AddParameters(ResamplingFilter filter, RichParameterList &par);

struct ResampleOutcome
{
    QString error;             ///< empty on success
    std::vector<LogLine> log;  ///< the run's figures, the whole filter's time last
    MeshModel *output = nullptr;
};

/// Resamples the current layer of `md` into a new current layer "<label> resampled" (the
/// reconstruction filter: SpreadEvenly set).
ResampleOutcome ResampleCurrentLayer(ResamplingFilter filter, MeshDocument &md, const RichParameterList &par,
                                     vcg::CallBackPos *cb);

} // namespace gaussphere_filter

#endif
