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

#include "resampling_log.h"

namespace gaussphere_filter {

QString PluginName();
QString FilterName();
QString FilterInfo();

/// The table's parameters for everyone, in dialog order; experts' ones keep their defaults.
void AddParameters(RichParameterList &par);

struct ResampleOutcome
{
    QString error;             ///< empty on success
    std::vector<LogLine> log;  ///< the run's figures, the whole filter's time last
    MeshModel *output = nullptr;
};

/// Resamples the current layer of `md` into a new current layer "<label> resampled".
ResampleOutcome ResampleCurrentLayer(MeshDocument &md, const RichParameterList &par, vcg::CallBackPos *cb);

} // namespace gaussphere_filter

#endif
