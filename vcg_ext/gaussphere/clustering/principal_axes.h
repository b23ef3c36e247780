// Principal axes of a 3x3 covariance matrix, largest eigenvalue first.
#ifndef VCG_EXT_GAUSSPHERE_PRINCIPAL_AXES_H
#define VCG_EXT_GAUSSPHERE_PRINCIPAL_AXES_H

#include <Eigen/Dense>

namespace vcg {
namespace gaussphere {

struct PrincipalAxes
{
    Eigen::Vector3d value;  ///< eigenvalues, value[0] >= value[1] >= value[2] >= 0
    Eigen::Matrix3d axis;   ///< column c: unit eigenvector of value[c]
};

inline PrincipalAxes ComputePrincipalAxes(const Eigen::Matrix3d &covariance)
{
    // computeDirect: closed form for 3x3, much faster than the iterative solver.
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
    solver.computeDirect(covariance);
    PrincipalAxes pa; // Eigen sorts ascending; reverse to largest first
    for (int c = 0; c < 3; ++c) {
        pa.value[c] = std::max(0.0, solver.eigenvalues()[2 - c]);
        pa.axis.col(c) = solver.eigenvectors().col(2 - c);
    }
    return pa;
}

/// Accumulates a covariance about a fixed centre.
struct CovarianceAccumulator
{
    Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
    double weight = 0;

    void Add(const Eigen::Vector3d &d, double w = 1.0) { sum.noalias() += w * d * d.transpose(); weight += w; }
    Eigen::Matrix3d Covariance() const { return weight > 0 ? Eigen::Matrix3d(sum / weight) : Eigen::Matrix3d::Zero(); }
};

} // namespace gaussphere
} // namespace vcg

#endif
