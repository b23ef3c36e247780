// Helpers for the whole-pipeline tests: running ResamplePointSet on a generated point
// set and checking the result's invariants.
#ifndef GAUSSPHERE_TESTS_ALGORITHM_PIPELINE_SUPPORT_H
#define GAUSSPHERE_TESTS_ALGORITHM_PIPELINE_SUPPORT_H

#include <gtest/gtest.h>

#include <limits>

#include <vcg_ext/gaussphere/clustering/principal_axes.h>
#include <vcg_ext/gaussphere/resampling.h>
#include <vcg_ext/gaussphere/surfels/surfel_mesh.h>
#include <vcg_ext/surfel_error/surfel_error.h>

#include "test_support.h"

// The pipeline and the metric on the test meshes are compiled once, in pipeline_support.cpp,
// not again in every test file that runs them: each copy costs about a minute under the
// sanitizers.
extern template vcg::gaussphere::ResamplingResult vcg::gaussphere::ResamplePointSet<vcg::gaussphere::OrientedPointMesh>(
    const vcg::gaussphere::OrientedPointMesh &, const vcg::gaussphere::ResamplingParams &, vcg::CallBackPos *);
extern template vcg::gaussphere::metric::SurfelErrorStats
vcg::gaussphere::metric::ComputeSurfelError<vcg::gaussphere::OrientedPointMesh, vcg::gaussphere::OrientedPointMesh>(
    const vcg::gaussphere::OrientedPointMesh &, const vcg::gaussphere::OrientedPointMesh &,
    const vcg::gaussphere::metric::SurfelErrorParams &, const vcg::gaussphere::metric::SurfelErrorAttributes &,
    std::vector<float> *, vcg::CallBackPos *);

namespace gstest {

/// ResamplePointSet on the point set, with the thread count set by the caller (ScopedThreadCount).
inline vcg::gaussphere::ResamplingResult Resample(const PointSet &s,
                                                  vcg::gaussphere::ResamplingParams p = {})
{
    vcg::gaussphere::OrientedPointMesh m;
    ToMesh(s, m);
    return vcg::gaussphere::ResamplePointSet(m, p);
}

/// Members of each surfel, from representative[].
inline std::vector<std::vector<int>> MembersOf(const vcg::gaussphere::ResamplingResult &r)
{
    std::vector<std::vector<int>> members(r.surfels.size());
    for (int i = 0; i < int(r.representative.size()); ++i)
        if (r.representative[i] >= 0) members[r.representative[i]].push_back(i);
    return members;
}

/// lambda1 / lambda2 of the positions of `members` (infinity when lambda2 = 0).
inline double ElongationOf(const PointSet &s, const std::vector<int> &members)
{
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (int i : members) mean += Eigen::Vector3d(s.points[i][0], s.points[i][1], s.points[i][2]);
    mean /= double(members.size());
    vcg::gaussphere::CovarianceAccumulator cov;
    for (int i : members) cov.Add(Eigen::Vector3d(s.points[i][0], s.points[i][1], s.points[i][2]) - mean);
    const vcg::gaussphere::PrincipalAxes pa = vcg::gaussphere::ComputePrincipalAxes(cov.Covariance());
    return pa.value[1] > 0 ? pa.value[0] / pa.value[1] : std::numeric_limits<double>::infinity();
}

/// The postconditions of ResamplePointSet: representative[] is -1 exactly for `skipped`
/// vertices and otherwise a surfel whose memberCount equals its number of vertices;
/// surfels have unit normals and tangent, orthogonal, non-zero axes with
/// |major| >= |minor|, and every member's projection lies inside its ellipse.
inline void ExpectValidResult(const vcg::gaussphere::ResamplingResult &r, const PointSet &s,
                              const std::vector<char> &skipped = {})
{
    ASSERT_EQ(int(r.representative.size()), s.Size());
    EXPECT_EQ(r.stats.outputCount, int(r.surfels.size()));
    EXPECT_GT(r.surfels.size(), 0u);
    const std::vector<std::vector<int>> members = MembersOf(r);
    for (int i = 0; i < s.Size(); ++i) {
        const bool skip = !skipped.empty() && skipped[i];
        if (skip) EXPECT_EQ(r.representative[i], -1) << "skipped vertex " << i;
        else {
            ASSERT_GE(r.representative[i], 0) << "vertex " << i;
            ASSERT_LT(r.representative[i], int(r.surfels.size())) << "vertex " << i;
        }
    }
    int bad = 0;
    for (size_t c = 0; c < r.surfels.size(); ++c) {
        const vcg::gaussphere::Surfel &f = r.surfels[c];
        const double a = f.majorAxis.Norm(), b = f.minorAxis.Norm();
        const bool ok = f.memberCount == int(members[c].size()) && members[c].size() > 0 &&
                        std::abs(f.normal.Norm() - 1) < 1e-5 && b > 0 && a >= b * (1 - 1e-6) &&
                        std::abs(Dot(f.majorAxis, f.normal)) < 1e-5 * a &&
                        std::abs(Dot(f.minorAxis, f.normal)) < 1e-5 * b &&
                        std::abs(Dot(f.majorAxis, f.minorAxis)) < 1e-5 * a * b;
        if (!ok && ++bad <= 5)
            ADD_FAILURE() << "surfel " << c << ": members " << members[c].size() << " memberCount " << f.memberCount
                          << " |n| " << f.normal.Norm() << " |major| " << a << " |minor| " << b;
        if (!ok) continue;
        for (int i : members[c]) {
            const P3 d = s.points[i] - f.position;
            const double x = Dot(d, f.majorAxis) / a, y = Dot(d, f.minorAxis) / b;
            if (x * x / (a * a) + y * y / (b * b) > 1 + 1e-4 && ++bad <= 5)
                ADD_FAILURE() << "vertex " << i << " lies outside the ellipse of surfel " << c;
        }
    }
    EXPECT_EQ(bad, 0) << "invalid surfels or uncovered members";
}

/// The error metric's figures (vcg_ext/surfel_error) for a resampling and its points.
struct Measured
{
    vcg::gaussphere::metric::SurfelErrorStats stats;
    std::vector<float> distance; ///< per input point, model units
};

/// The metric's figures for `r` against `s`, with r's ellipses, blend scales and representatives.
inline Measured Measure(const PointSet &s, const vcg::gaussphere::ResamplingResult &r)
{
    vcg::gaussphere::OrientedPointMesh input, surfels;
    ToMesh(s, input);
    vcg::gaussphere::WriteSurfels(r.surfels, surfels);
    std::vector<vcg::Point3f> major, minor;
    std::vector<float> blendScale;
    for (const vcg::gaussphere::Surfel &surfel : r.surfels) {
        major.push_back(surfel.majorAxis);
        minor.push_back(surfel.minorAxis);
        blendScale.push_back(surfel.blendScale);
    }
    vcg::gaussphere::metric::SurfelErrorAttributes attributes;
    attributes.ellipseMajorAxes = &major;
    attributes.ellipseMinorAxes = &minor;
    attributes.blendScale = &blendScale;
    const std::vector<int> representative(r.representative.begin(), r.representative.end());
    attributes.representative = &representative;
    Measured m;
    m.stats = vcg::gaussphere::metric::ComputeSurfelError(input, surfels, vcg::gaussphere::metric::SurfelErrorParams(), attributes, &m.distance);
    return m;
}

} // namespace gstest

#endif
