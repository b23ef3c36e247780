#include "point_sets.h"

#include <fstream>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include <wrap/io_trimesh/export_ply.h>
#include <wrap/io_trimesh/import_ply.h>

namespace gsbench {

void LoadPointSet(const std::string &path, PointMesh &mesh)
{
    int mask = 0;
    if (vcg::tri::io::ImporterPLY<PointMesh>::Open(mesh, path.c_str(), mask) != 0)
        throw std::runtime_error("cannot read " + path);
    // vcg leaves absent normals uninitialised: every input and output measured here has them.
    if (!(mask & vcg::tri::io::Mask::IOM_VERTNORMAL)) throw std::runtime_error(path + " has no per-vertex normals");
    if (!(mask & vcg::tri::io::Mask::IOM_VERTRADIUS))
        for (auto &v : mesh.vert) v.R() = 0;
    vcg::tri::UpdateBounding<PointMesh>::Box(mesh);
}

void SavePointSet(PointMesh &mesh, const std::string &path, bool withRadius)
{
    int mask = vcg::tri::io::Mask::IOM_VERTNORMAL;
    if (withRadius) mask |= vcg::tri::io::Mask::IOM_VERTRADIUS;
    if (vcg::tri::io::ExporterPLY<PointMesh>::Save(mesh, path.c_str(), mask, true) != 0)
        throw std::runtime_error("cannot write " + path);
}

int PlyVertexCount(const std::string &path)
{
    std::ifstream in(path, std::ios::binary);
    std::string line;
    while (std::getline(in, line) && line.rfind("end_header", 0) != 0) {
        std::istringstream words(line);
        std::string element, name;
        int count = -1;
        if (words >> element >> name >> count && element == "element" && name == "vertex") return count;
    }
    return -1;
}

void CopySubset(const PointMesh &from, const std::vector<int> &indices, PointMesh &to)
{
    to.Clear();
    auto vi = vcg::tri::Allocator<PointMesh>::AddVertices(to, indices.size());
    for (int i : indices) {
        vi->P() = from.vert[i].cP();
        vi->N() = from.vert[i].cN();
        vi->R() = 0;
        ++vi;
    }
    vcg::tri::UpdateBounding<PointMesh>::Box(to);
}

vcg::gaussphere::metric::SurfelErrorAttributes SimplifiedSet::Attributes() const
{
    vcg::gaussphere::metric::SurfelErrorAttributes a;
    if (!major.empty()) {
        a.ellipseMajorAxes = &major;
        a.ellipseMinorAxes = &minor;
    }
    if (!representative.empty()) a.representative = &representative;
    if (!blendScale.empty()) a.blendScale = &blendScale;
    return a;
}

void MakeIdentitySet(const PointMesh &input, SimplifiedSet &set)
{
    std::vector<int> all(input.vert.size());
    std::iota(all.begin(), all.end(), 0);
    CopySubset(input, all, set.mesh);
    set.major.clear();
    set.minor.clear();
    set.blendScale.clear();
    // Each point is represented by itself, so the own-surfel shape error is exactly 0.
    set.representative = all;
}

vcg::gaussphere::metric::SurfelErrorStats Evaluate(const PointMesh &input, const SimplifiedSet &set,
                                    std::vector<float> *perPointDistance)
{
    return vcg::gaussphere::metric::ComputeSurfelError(input, set.mesh, vcg::gaussphere::metric::SurfelErrorParams(), set.Attributes(),
                                        perPointDistance);
}

} // namespace gsbench
