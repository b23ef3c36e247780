#include "layer_surfels.h"

#include <meshlab_glue/meshlab_document.h>
#include <vcg_ext/gaussphere/surfels/surfel_mesh.h>

#include <algorithm>
#include <cstring>

namespace splat {
namespace {

using vcg::gaussphere::kMajorAxisAttribute;
using vcg::gaussphere::kMinorAxisAttribute;

using AxisHandle = CMeshO::PerVertexAttributeHandle<Point3m>;
using OffsetHandle = CMeshO::PerVertexAttributeHandle<float>;

// Both ellipse attribute handles, valid only when the layer has both.
bool findEllipseAttributes(const MeshModel &layer, AxisHandle &major, AxisHandle &minor)
{
    CMeshO &mesh = const_cast<CMeshO &>(layer.cm); // FindPerVertexAttribute takes a non-const mesh
    major = vcg::tri::Allocator<CMeshO>::FindPerVertexAttribute<Point3m>(mesh, kMajorAxisAttribute);
    minor = vcg::tri::Allocator<CMeshO>::FindPerVertexAttribute<Point3m>(mesh, kMinorAxisAttribute);
    return vcg::tri::Allocator<CMeshO>::IsValidHandle(mesh, major) &&
           vcg::tri::Allocator<CMeshO>::IsValidHandle(mesh, minor);
}

// The fit offset attribute handle, valid only when the layer has it.
bool findFitOffsets(const MeshModel &layer, OffsetHandle &offsets)
{
    CMeshO &mesh = const_cast<CMeshO &>(layer.cm);
    offsets = vcg::tri::Allocator<CMeshO>::FindPerVertexAttribute<float>(mesh, vcg::gaussphere::kFitOffsetAttribute);
    return vcg::tri::Allocator<CMeshO>::IsValidHandle(mesh, offsets);
}

bool hasRadii(const MeshModel &layer)
{
    return layer.hasDataMask(MeshModel::MM_VERTRADIUS);
}

bool hasColors(const MeshModel &layer)
{
    return layer.hasDataMask(MeshModel::MM_VERTCOLOR);
}

// FNV-1a over 32-bit words rather than bytes: fast enough to run on every frame over a few
// million values, and any edit of a value changes it.
class Fingerprint
{
public:
    template <typename T>
    void add(const T &value)
    {
        static_assert(sizeof(T) % sizeof(std::uint32_t) == 0, "fingerprint whole words");
        std::uint32_t words[sizeof(T) / sizeof(std::uint32_t)];
        std::memcpy(words, &value, sizeof(T));
        for (std::uint32_t w : words)
            hash = (hash ^ w) * 0x100000001b3ULL;
    }
    std::uint64_t value() const { return hash; }

private:
    std::uint64_t hash = 0xcbf29ce484222325ULL;
};

} // namespace

bool layerHasNormals(const MeshModel &layer)
{
    for (const CVertexO &v : layer.cm.vert)
        if (!v.IsD() && v.cN() != Point3m(0, 0, 0))
            return true;
    return false;
}

SurfelArrays surfelsOfLayer(const MeshModel &layer, const LayerSplatOptions &options, std::size_t &skipped,
                            const ProgressCallback &progress)
{
    SurfelArrays surfels;
    const std::size_t count = std::size_t(layer.cm.vn);
    surfels.positions.reserve(3 * count);
    surfels.normals.reserve(3 * count);
    if (hasColors(layer))
        surfels.colors.reserve(4 * count);
    AxisHandle major, minor;
    const bool hasEllipses = findEllipseAttributes(layer, major, minor);
    OffsetHandle offset;
    const bool hasOffsets = !options.atFittedPositions && findFitOffsets(layer, offset);
    std::vector<float> fitOffsets; // per surfel when the layer has them and they are to be undone
    std::vector<float> radii; // per surfel; 0 = not known, estimate from neighbours
    for (const CVertexO &v : layer.cm.vert) {
        if (v.IsD())
            continue;
        for (int c = 0; c < 3; ++c) {
            surfels.positions.push_back(v.cP()[c]);
            surfels.normals.push_back(v.cN()[c]);
        }
        if (hasColors(layer))
            for (int c = 0; c < 4; ++c)
                surfels.colors.push_back(v.cC()[c]);
        if (hasOffsets)
            fitOffsets.push_back(offset[v]);
        if (hasEllipses) {
            for (int c = 0; c < 3; ++c) {
                surfels.majorAxes.push_back(major[v][c]);
                surfels.minorAxes.push_back(minor[v][c]);
            }
        } else {
            radii.push_back(hasRadii(layer) && v.cR() > 0 ? v.cR() : 0.0f);
        }
    }
    undoFitOffsets(surfels, fitOffsets);
    if (!hasEllipses) {
        if (std::find(radii.begin(), radii.end(), 0.0f) != radii.end()) {
            const std::vector<float> spacing = nearestNeighbourRadii(surfels.positions, options.neighbours, progress);
            for (std::size_t i = 0; i < radii.size(); ++i)
                if (radii[i] == 0.0f)
                    radii[i] = spacing[i];
        }
        assignCircularFrames(surfels, radii);
    }
    skipped = removeUnusableSurfels(surfels);
    return surfels;
}

std::uint64_t layerFingerprint(const MeshModel &layer, const LayerSplatOptions &options)
{
    Fingerprint fingerprint;
    AxisHandle major, minor;
    const bool hasEllipses = findEllipseAttributes(layer, major, minor);
    OffsetHandle offset;
    const bool hasOffsets = !options.atFittedPositions && findFitOffsets(layer, offset);
    fingerprint.add(layer.cm.vn);
    fingerprint.add(options.neighbours);
    fingerprint.add(std::uint32_t(hasEllipses) | std::uint32_t(hasRadii(layer)) << 1 |
                    std::uint32_t(hasColors(layer)) << 2 | std::uint32_t(hasOffsets) << 3);
    for (const CVertexO &v : layer.cm.vert) {
        if (v.IsD())
            continue;
        fingerprint.add(v.cP());
        fingerprint.add(v.cN());
        if (hasColors(layer))
            fingerprint.add(v.cC());
        if (hasRadii(layer))
            fingerprint.add(v.cR());
        if (hasEllipses) {
            fingerprint.add(major[v]);
            fingerprint.add(minor[v]);
        }
        if (hasOffsets)
            fingerprint.add(offset[v]);
    }
    return fingerprint.value();
}

} // namespace splat
