// The one copy of the pipeline and the metric on the test meshes (pipeline_support.h).
#include "pipeline_support.h"

template vcg::gaussphere::ResamplingResult vcg::gaussphere::ResamplePointSet<vcg::gaussphere::OrientedPointMesh>(
    const vcg::gaussphere::OrientedPointMesh &, const vcg::gaussphere::ResamplingParams &, vcg::CallBackPos *);
template vcg::gaussphere::metric::SurfelErrorStats
vcg::gaussphere::metric::ComputeSurfelError<vcg::gaussphere::OrientedPointMesh, vcg::gaussphere::OrientedPointMesh>(
    const vcg::gaussphere::OrientedPointMesh &, const vcg::gaussphere::OrientedPointMesh &,
    const vcg::gaussphere::metric::SurfelErrorParams &, const vcg::gaussphere::metric::SurfelErrorAttributes &,
    std::vector<float> *, vcg::CallBackPos *);
