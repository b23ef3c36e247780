// A nanoflann kd-tree over a vector of float points: the spacing estimate, the border points' cover
// check and gstile_compare.
#ifndef GSTILE_POINT_TREE_H
#define GSTILE_POINT_TREE_H

#include <array>
#include <vector>

#include <nanoflann.hpp>

namespace gstile {

struct PointCloud
{
    const std::vector<std::array<float, 3>> &points;
    std::size_t kdtree_get_point_count() const { return points.size(); }
    float kdtree_get_pt(std::size_t i, std::size_t axis) const { return points[i][axis]; }
    template <class Box>
    bool kdtree_get_bbox(Box &) const { return false; }
};

/// PointTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16)) builds the index (nanoflann 1.4 on).
typedef nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, PointCloud>, PointCloud, 3> PointTree;

} // namespace gstile

#endif
