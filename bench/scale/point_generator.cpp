#include "point_generator.h"

#include <vcg_ext/gaussphere/neighbors/point_grid.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <stdexcept>
#include <vector>

#include <wrap/io_trimesh/import_ply.h>

namespace gsscale {

using vcg::gaussphere::OrientedPointMesh;

namespace {

const double kPi = 3.14159265358979323846;

/// Uniform doubles and Gaussians from mt19937_64, converted by hand so that the stream is
/// the same with every standard library.
class Random
{
public:
    explicit Random(std::uint64_t seed) : engine_(seed) {}
    double Uniform() { return double(engine_() >> 11) * 0x1.0p-53; } // [0, 1)
    double Gaussian()
    {
        // Box-Muller; 1 - Uniform() lies in (0, 1], so the logarithm is finite.
        const double r = std::sqrt(-2.0 * std::log(1.0 - Uniform()));
        return r * std::cos(2.0 * kPi * Uniform());
    }

private:
    std::mt19937_64 engine_;
};

/// Sets vertex i of `out`; adds noise of standard deviation `sigma` to the position.
void SetPoint(OrientedPointMesh &out, size_t i, const vcg::Point3d &p, const vcg::Point3d &n, double sigma,
              Random &random)
{
    vcg::Point3d q = p;
    if (sigma > 0)
        for (int a = 0; a < 3; ++a) q[a] += sigma * random.Gaussian();
    out.vert[i].P() = vcg::Point3f::Construct(q);
    out.vert[i].N() = vcg::Point3f::Construct(n);
}

void SampleMesh(const GeneratorParams &params, OrientedPointMesh &out)
{
    const std::string path = params.dataDir + "/" + params.shape + "_mesh.ply";
    // The source is dropped when this function returns: the benchmark's "input layer" is
    // then the generated points alone.
    std::unique_ptr<OrientedPointMesh> source(new OrientedPointMesh);
    int mask = 0;
    if (vcg::tri::io::ImporterPLY<OrientedPointMesh>::Open(*source, path.c_str(), mask) != 0)
        throw std::runtime_error("cannot read " + path);
    if (!(mask & vcg::tri::io::Mask::IOM_VERTNORMAL)) throw std::runtime_error(path + " has no vertex normals");

    // Faces by cumulative area: a uniform draw in [0, total) picks a face by area.
    std::vector<double> cumulative;
    cumulative.reserve(source->face.size());
    double total = 0;
    for (const auto &f : source->face) {
        const vcg::Point3d a = vcg::Point3d::Construct(f.cP(0)), b = vcg::Point3d::Construct(f.cP(1)),
                           c = vcg::Point3d::Construct(f.cP(2));
        total += 0.5 * ((b - a) ^ (c - a)).Norm();
        cumulative.push_back(total);
    }
    if (!(total > 0)) throw std::runtime_error(path + " has no triangle with a positive area");
    source->bbox.SetNull();
    for (const auto &v : source->vert) source->bbox.Add(v.cP());
    const double sigma = params.noise * source->bbox.Diag();

    Random random(params.seed);
    vcg::tri::Allocator<OrientedPointMesh>::AddVertices(out, size_t(params.count));
    for (size_t i = 0; i < size_t(params.count); ++i) {
        const size_t fi = std::min(cumulative.size() - 1,
            size_t(std::upper_bound(cumulative.begin(), cumulative.end(), random.Uniform() * total) - cumulative.begin()));
        const auto &f = source->face[fi];
        // Uniform barycentric coordinates (the square-root warp).
        const double r = std::sqrt(random.Uniform()), s = random.Uniform();
        const double w[3] = {1 - r, r * (1 - s), r * s};
        vcg::Point3d p(0, 0, 0), n(0, 0, 0);
        for (int k = 0; k < 3; ++k) {
            p += vcg::Point3d::Construct(f.cV(k)->cP()) * w[k];
            n += vcg::Point3d::Construct(f.cV(k)->cN()) * w[k];
        }
        const double len = n.Norm();
        // Opposite normals across a thin face can cancel; the face normal then stands in.
        if (len > 1e-12) n /= len;
        else n = vcg::Point3d::Construct(((f.cV(1)->cP() - f.cV(0)->cP()) ^ (f.cV(2)->cP() - f.cV(0)->cP())).Normalize());
        SetPoint(out, i, p, n, sigma, random);
    }
}

void SampleDrilledBox(const GeneratorParams &params, OrientedPointMesh &out)
{
    // Cube [-1,1]^3 minus the cylinder x^2 + y^2 < R^2 along z.
    const double R = 0.5;
    const double sideArea = 4, capArea = 4 - kPi * R * R, wallArea = 2 * kPi * R * 2;
    // Surfaces 0-3: x = +-1, y = +-1; 4-5: z = +-1 with the hole; 6: the hole's wall.
    const double area[7] = {sideArea, sideArea, sideArea, sideArea, capArea, capArea, wallArea};
    double cumulative[7], total = 0;
    for (int s = 0; s < 7; ++s) cumulative[s] = total += area[s];
    const double sigma = params.noise * 2 * std::sqrt(3.0);

    Random random(params.seed);
    vcg::tri::Allocator<OrientedPointMesh>::AddVertices(out, size_t(params.count));
    for (size_t i = 0; i < size_t(params.count); ++i) {
        const double pick = random.Uniform() * total;
        const int surface = int(std::min<std::ptrdiff_t>(6, std::upper_bound(cumulative, cumulative + 7, pick) - cumulative));
        vcg::Point3d p, n;
        if (surface < 4) {
            const int axis = surface / 2;            // 0: x, 1: y
            const double sign = surface % 2 ? -1 : 1;
            const double u = 2 * random.Uniform() - 1, z = 2 * random.Uniform() - 1;
            p = axis == 0 ? vcg::Point3d(sign, u, z) : vcg::Point3d(u, sign, z);
            n = axis == 0 ? vcg::Point3d(sign, 0, 0) : vcg::Point3d(0, sign, 0);
        } else if (surface < 6) {
            const double sign = surface == 4 ? 1 : -1;
            double x, y;
            do { x = 2 * random.Uniform() - 1; y = 2 * random.Uniform() - 1; } while (x * x + y * y < R * R);
            p = vcg::Point3d(x, y, sign);
            n = vcg::Point3d(0, 0, sign);
        } else {
            const double theta = 2 * kPi * random.Uniform(), z = 2 * random.Uniform() - 1;
            p = vcg::Point3d(R * std::cos(theta), R * std::sin(theta), z);
            n = vcg::Point3d(-std::cos(theta), -std::sin(theta), 0); // the wall faces the axis
        }
        SetPoint(out, i, p, n, sigma, random);
    }
}

/// Sorts the vertices along a Z-order curve of their positions (21 bits per axis).
void SortMorton(OrientedPointMesh &mesh)
{
    vcg::Box3f box;
    for (const auto &v : mesh.vert) box.Add(v.cP());
    const double scale = double((1 << 21) - 1) / std::max(1e-30, double(std::max({box.DimX(), box.DimY(), box.DimZ()})));
    std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(mesh.vert.size());
    for (size_t i = 0; i < keyed.size(); ++i) {
        std::uint64_t key = 0;
        for (int a = 0; a < 3; ++a) key |= vcg::gaussphere::MortonSpread(std::uint64_t((mesh.vert[i].cP()[a] - box.min[a]) * scale)) << a;
        keyed[i] = {key, std::uint32_t(i)};
    }
    std::sort(keyed.begin(), keyed.end());
    std::vector<vcg::Point3f> p(keyed.size()), n(keyed.size());
    for (size_t i = 0; i < keyed.size(); ++i) { p[i] = mesh.vert[keyed[i].second].cP(); n[i] = mesh.vert[keyed[i].second].cN(); }
    for (size_t i = 0; i < keyed.size(); ++i) { mesh.vert[i].P() = p[i]; mesh.vert[i].N() = n[i]; }
}

} // namespace

void GeneratePoints(const GeneratorParams &params, OrientedPointMesh &out)
{
    if (params.count < 2 || params.count > 2000000000LL) throw std::runtime_error("point count out of range");
    out.Clear();
    if (params.shape == "drilled-box") SampleDrilledBox(params, out);
    else SampleMesh(params, out);
    if (params.order == "morton") SortMorton(out);
    else if (params.order != "random") throw std::runtime_error("unknown order " + params.order);
    const size_t count = out.vert.size();
    for (size_t i = count - size_t(std::min<long long>(params.coincident, (long long)count - 1)); i < count; ++i)
        out.vert[i].P() = out.vert[0].cP(), out.vert[i].N() = out.vert[0].cN();
    vcg::tri::UpdateBounding<OrientedPointMesh>::Box(out);
    if (params.outlier > 0) {
        const vcg::Point3f away = out.bbox.max + vcg::Point3f(1, 1, 1) * float(params.outlier * out.bbox.Diag() / std::sqrt(3.0));
        out.vert[count - 1].P() = away;
        vcg::tri::UpdateBounding<OrientedPointMesh>::Box(out);
    }
}

void WriteOrientedPly(const OrientedPointMesh &mesh, const std::string &path)
{
    std::FILE *f = std::fopen(path.c_str(), "wb");
    if (!f) throw std::runtime_error("cannot write " + path);
    std::fprintf(f, "ply\nformat binary_little_endian 1.0\ncomment gsscale generator\nelement vertex %d\n"
                    "property float x\nproperty float y\nproperty float z\n"
                    "property float nx\nproperty float ny\nproperty float nz\nend_header\n", mesh.vn);
    bool ok = true;
    for (const auto &v : mesh.vert) {
        if (v.IsD()) continue;
        const float record[6] = {v.cP()[0], v.cP()[1], v.cP()[2], v.cN()[0], v.cN()[1], v.cN()[2]};
        ok = ok && std::fwrite(record, sizeof(record), 1, f) == 1; // x86 and ARM: little endian
    }
    ok = std::fclose(f) == 0 && ok;
    if (!ok) throw std::runtime_error("error writing " + path);
}

} // namespace gsscale
