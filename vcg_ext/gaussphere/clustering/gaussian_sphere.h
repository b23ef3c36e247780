// Subdivided Gaussian sphere: a regular triangulation of the unit sphere with O(1)
// lookup of the triangle that contains a unit normal.
//
// Construction: every face of the icosahedron inscribed in the unit sphere is cut into
// (n-1)^2 triangles by n-1 segments per edge; the vertices are projected onto the sphere
// along rays from the centre (gnomonic projection). The icosahedron has the most faces of
// the regular polyhedra, so the projection distorts its triangles least. A normal is located
// by intersecting its ray with the face plane of its base face and reading the barycentric
// grid cell there, so lookup costs one 3x3 product.
//
// Level n and d_max. The paper gives d_max = sqrt(7*pi^2 / (8 (n-1)^2)) as "the maximal
// length of a Gaussian edge" for level n and varies n = 8, 16, 24; the 1/(n-1) scaling
// is n-1 segments per base edge, which is what this class builds. The formula is 2.2x
// the true maximal chord of the triangulation (see MaxEdgeLength()). The resampler uses the
// formula's d_max for the cone of normals and for the propagation radius, as the paper does,
// since that reading reproduces the paper's neighbourhood sizes (6-16 of 16) and counts.
#ifndef VCG_EXT_GAUSSPHERE_GAUSSIAN_SPHERE_H
#define VCG_EXT_GAUSSPHERE_GAUSSIAN_SPHERE_H

#include <algorithm>
#include <cassert>
#include <cmath>
#include <vector>

#include <vcg/space/point3.h>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <vcg_ext/gaussphere/support/cpu_dispatch.h>

namespace vcg {
namespace gaussphere {

class GaussianSphere
{
public:
    typedef vcg::Point3f Point3;

    /// level >= 2: the paper's n; each base edge is cut into level-1 segments.
    explicit GaussianSphere(int level) : level_(std::max(2, level)), segments_(level_ - 1)
    {
        BuildBaseFaces();
    }

    int Level() const { return level_; }
    int BaseFaceCount() const { return int(faces_.size()); }

    /// Triangle ids lie in [0, TriangleIdCount()); every id denotes one triangle.
    int TriangleIdCount() const { return BaseFaceCount() * segments_ * segments_; }

    /// The paper's d_max for this level (a chord length on the unit sphere).
    double PaperMaxEdgeLength() const { return PaperMaxEdgeLength(level_); }
    static double PaperMaxEdgeLength(int level)
    {
        const double pi = 3.14159265358979323846;
        const double m = std::max(1, level - 1);
        return std::sqrt(7.0 * pi * pi / (8.0 * m * m));
    }

    /// Index of the triangle containing the direction `normal` (need not be unit length,
    /// must be non-zero and finite). Points on shared edges or vertices go to one
    /// deterministic neighbour.
    int TriangleOf(const Point3 &normal) const
    {
        const int f = BaseFaceOf(normal);
        const Face &face = faces_[f];
        // Barycentric coordinates of the ray's hit on the face plane, up to scale.
        double b[3];
        for (int r = 0; r < 3; ++r)
            b[r] = face.inv[r][0] * normal[0] + face.inv[r][1] * normal[1] + face.inv[r][2] * normal[2];
        const double s = b[0] + b[1] + b[2];
        const double u = std::max(0.0, b[1] / s) * segments_;
        const double v = std::max(0.0, b[2] / s) * segments_;
        int i = std::min(int(u), segments_ - 1);
        int j = std::min(int(v), segments_ - 1 - i);
        const bool upper = (u - i) + (v - j) > 1.0 && i + j < segments_ - 1;
        return f * segments_ * segments_ + LocalIndex(i, j, upper);
    }

    /// triangles[i] = TriangleOf(normals[i]) for i in [0, count): the same ids, eight normals at a
    /// time where the CPU has AVX2 (the same float and double
    /// operations in the same order as TriangleOf, so the same triangles), at about a third of
    /// TriangleOf's time per normal.
    void TrianglesOf(const Point3 *normals, int count, int *triangles) const
    {
        int i = 0;
#ifdef GAUSSPHERE_X86_DISPATCH
        if (Avx2Kernels()) i = TrianglesOfAvx2(normals, count, triangles);
#endif
        for (; i < count; ++i) triangles[i] = TriangleOf(normals[i]);
    }

    /// Whether TrianglesOf runs its AVX2 kernel: by default when the CPU has AVX2. Setting it to
    /// false runs TriangleOf alone (same results), e.g. to test the kernel against it.
    static bool &Avx2Kernels()
    {
        static bool on = CpuHasAvx2();
        return on;
    }

    /// The three unit vertices of triangle `id`, counter-clockwise seen from outside.
    void TriangleVertices(int id, Point3 &a, Point3 &b, Point3 &c) const
    {
        const int per = segments_ * segments_;
        const Face &face = faces_[id / per];
        int local = id % per;
        // Rows i hold 2*(m-i)-1 triangles: m-i lower ones and m-i-1 upper ones.
        int i = 0;
        while (local >= 2 * (segments_ - i) - 1) { local -= 2 * (segments_ - i) - 1; ++i; }
        const bool upper = local >= segments_ - i;
        const int j = upper ? local - (segments_ - i) : local;
        if (!upper) {
            a = GridPoint(face, i, j); b = GridPoint(face, i + 1, j); c = GridPoint(face, i, j + 1);
        } else {
            a = GridPoint(face, i + 1, j); b = GridPoint(face, i + 1, j + 1); c = GridPoint(face, i, j + 1);
        }
    }

    /// Longest edge (chord) of the actual triangulation.
    double MaxEdgeLength() const
    {
        double longest = 0;
        for (int id = 0; id < TriangleIdCount(); ++id) {
            Point3 a, b, c;
            TriangleVertices(id, a, b, c);
            longest = std::max({longest, double((a - b).Norm()), double((b - c).Norm()), double((c - a).Norm())});
        }
        return longest;
    }

private:
    struct Face
    {
        Point3 v[3];
        double inv[3][3]; // inverse of the matrix whose columns are v[0], v[1], v[2]
    };

    int LocalIndex(int i, int j, bool upper) const
    {
        // Row i starts after sum_{r<i} (2(m-r)-1) = i(2m-i) triangles.
        const int rowStart = i * (2 * segments_ - i);
        return rowStart + (upper ? (segments_ - i) + j : j);
    }

    Point3 GridPoint(const Face &f, int i, int j) const
    {
        const float u = float(i) / segments_, v = float(j) / segments_;
        Point3 p = f.v[0] * (1 - u - v) + f.v[1] * u + f.v[2] * v;
        return p.Normalize();
    }

    int BaseFaceOf(const Point3 &n) const
    {
        // The containing face is the one whose centre is nearest, the
        // first of equals. Four faces at a time where SSE2 is there (x86-64 always): the
        // same float products and sums as Point3::dot, so the same face.
#if defined(__SSE2__)
        const __m128 x = _mm_set1_ps(n[0]), y = _mm_set1_ps(n[1]), z = _mm_set1_ps(n[2]);
        __m128 bestDot = _mm_set1_ps(-2.f);
        __m128i bestFace = _mm_setzero_si128(), face = _mm_setr_epi32(0, 1, 2, 3);
        for (int g = 0; g < kIcosahedronFaces / 4; ++g) {
            const __m128 d = _mm_add_ps(_mm_add_ps(_mm_mul_ps(x, _mm_loadu_ps(centreX_ + 4 * g)),
                                                   _mm_mul_ps(y, _mm_loadu_ps(centreY_ + 4 * g))),
                                        _mm_mul_ps(z, _mm_loadu_ps(centreZ_ + 4 * g)));
            const __m128 better = _mm_cmpgt_ps(d, bestDot);
            bestDot = _mm_or_ps(_mm_and_ps(better, d), _mm_andnot_ps(better, bestDot));
            const __m128i take = _mm_castps_si128(better);
            bestFace = _mm_or_si128(_mm_and_si128(take, face), _mm_andnot_si128(take, bestFace));
            face = _mm_add_epi32(face, _mm_set1_epi32(4));
        }
        float laneDot[4];
        int laneFace[4];
        _mm_storeu_ps(laneDot, bestDot);
        _mm_storeu_si128(reinterpret_cast<__m128i *>(laneFace), bestFace);
        int best = laneFace[0];
        for (int l = 1; l < 4; ++l)
            if (laneDot[l] > laneDot[0] || (laneDot[l] == laneDot[0] && laneFace[l] < best)) {
                laneDot[0] = laneDot[l];
                best = laneFace[l];
            }
        return best;
#else
        int best = 0;
        float bestDot = -2;
        for (int f = 0; f < kIcosahedronFaces; ++f) {
            const float d = n[0] * centreX_[f] + n[1] * centreY_[f] + n[2] * centreZ_[f];
            if (d > bestDot) { bestDot = d; best = f; }
        }
        return best;
#endif
    }

#ifdef GAUSSPHERE_X86_DISPATCH
    /// TrianglesOf's kernel, whole groups of eight; returns where it stopped.
    /// The face: the largest dot product with the face centres, the first of equals (TriangleOf
    /// takes the same in four lanes, then the lowest face among equal lanes). The barycentric
    /// coordinates in double, four lanes at a time, from the face's row of `faceInverse_`.
    __attribute__((target("avx2"))) int TrianglesOfAvx2(const Point3 *normals, int count, int *triangles) const
    {
        const __m256i gather = _mm256_setr_epi32(0, 3, 6, 9, 12, 15, 18, 21); // floats per Point3: 3
        const __m128i seg = _mm_set1_epi32(segments_), segMinus1 = _mm_set1_epi32(segments_ - 1);
        const __m256d segments = _mm256_set1_pd(segments_), zero = _mm256_setzero_pd(), one = _mm256_set1_pd(1.0);
        const __m256d all = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
        int g = 0;
        for (; g + 8 <= count; g += 8) {
            const float *base = &normals[g][0];
            const __m256 x = _mm256_i32gather_ps(base, gather, 4), y = _mm256_i32gather_ps(base + 1, gather, 4),
                         z = _mm256_i32gather_ps(base + 2, gather, 4);
            __m256 bestDot = _mm256_set1_ps(-2.f);
            __m256i bestFace = _mm256_setzero_si256();
            for (int f = 0; f < kIcosahedronFaces; ++f) {
                const __m256 d = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(x, _mm256_set1_ps(centreX_[f])),
                                                             _mm256_mul_ps(y, _mm256_set1_ps(centreY_[f]))),
                                               _mm256_mul_ps(z, _mm256_set1_ps(centreZ_[f])));
                const __m256 better = _mm256_cmp_ps(d, bestDot, _CMP_GT_OQ);
                bestDot = _mm256_blendv_ps(bestDot, d, better);
                bestFace = _mm256_blendv_epi8(bestFace, _mm256_set1_epi32(f), _mm256_castps_si256(better));
            }
            for (int half = 0; half < 2; ++half) {
                const __m128i face = half ? _mm256_extracti128_si256(bestFace, 1) : _mm256_castsi256_si128(bestFace);
                const __m256d nx = _mm256_cvtps_pd(half ? _mm256_extractf128_ps(x, 1) : _mm256_castps256_ps128(x));
                const __m256d ny = _mm256_cvtps_pd(half ? _mm256_extractf128_ps(y, 1) : _mm256_castps256_ps128(y));
                const __m256d nz = _mm256_cvtps_pd(half ? _mm256_extractf128_ps(z, 1) : _mm256_castps256_ps128(z));
                const __m128i row = _mm_mullo_epi32(face, _mm_set1_epi32(9));
                // Masked gathers with a zero source: the plain ones leave GCC 12 warning of an
                // undefined source.
                __m256d b[3];
                for (int r = 0; r < 3; ++r) {
                    __m256d entry[3];
                    for (int c = 0; c < 3; ++c)
                        entry[c] = _mm256_mask_i32gather_pd(zero, faceInverse_.data() + 3 * r + c, row, all, 8);
                    b[r] = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(entry[0], nx), _mm256_mul_pd(entry[1], ny)),
                                         _mm256_mul_pd(entry[2], nz));
                }
                const __m256d sum = _mm256_add_pd(_mm256_add_pd(b[0], b[1]), b[2]);
                // std::max(0.0, q) is q > 0 ? q : 0 (NaN: 0), as is max_pd(q, 0).
                const __m256d u = _mm256_mul_pd(_mm256_max_pd(_mm256_div_pd(b[1], sum), zero), segments);
                const __m256d v = _mm256_mul_pd(_mm256_max_pd(_mm256_div_pd(b[2], sum), zero), segments);
                const __m128i i = _mm_min_epi32(_mm256_cvttpd_epi32(u), segMinus1);
                const __m128i j = _mm_min_epi32(_mm256_cvttpd_epi32(v), _mm_sub_epi32(segMinus1, i));
                const __m256d rest = _mm256_add_pd(_mm256_sub_pd(u, _mm256_cvtepi32_pd(i)), _mm256_sub_pd(v, _mm256_cvtepi32_pd(j)));
                // The comparison's 64-bit lane masks, narrowed to 32 bits.
                const __m128i beyond = _mm256_castsi256_si128(_mm256_permutevar8x32_epi32(
                    _mm256_castpd_si256(_mm256_cmp_pd(rest, one, _CMP_GT_OQ)), _mm256_setr_epi32(0, 2, 4, 6, 0, 2, 4, 6)));
                const __m128i upper = _mm_and_si128(beyond, _mm_cmplt_epi32(_mm_add_epi32(i, j), segMinus1));
                // LocalIndex(i, j, upper) of the face's first id.
                const __m128i rowStart = _mm_mullo_epi32(i, _mm_sub_epi32(_mm_add_epi32(seg, seg), i));
                const __m128i local = _mm_add_epi32(_mm_add_epi32(rowStart, j), _mm_and_si128(upper, _mm_sub_epi32(seg, i)));
                const __m128i id = _mm_add_epi32(_mm_mullo_epi32(face, _mm_mullo_epi32(seg, seg)), local);
                _mm_storeu_si128(reinterpret_cast<__m128i *>(triangles + g + 4 * half), id);
            }
        }
        return g;
    }
#endif

    void AddFace(Point3 a, Point3 b, Point3 c)
    {
        if (((b - a) ^ (c - a)).dot(a + b + c) < 0) std::swap(b, c);
        Face f;
        f.v[0] = a; f.v[1] = b; f.v[2] = c;
        const double m[3][3] = {{a[0], b[0], c[0]}, {a[1], b[1], c[1]}, {a[2], b[2], c[2]}};
        const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
                         - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
                         + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
        for (int r = 0; r < 3; ++r)
            for (int col = 0; col < 3; ++col) {
                // inverse = adjugate / det; adjugate[r][col] = cofactor[col][r]
                const int r1 = (col + 1) % 3, r2 = (col + 2) % 3, c1 = (r + 1) % 3, c2 = (r + 2) % 3;
                f.inv[r][col] = (m[r1][c1] * m[r2][c2] - m[r1][c2] * m[r2][c1]) / det;
            }
        for (int r = 0; r < 3; ++r)
            for (int col = 0; col < 3; ++col) faceInverse_.push_back(f.inv[r][col]);
        const Point3 centre = (a + b + c).Normalize();
        const int id = int(faces_.size());
        centreX_[id] = centre[0];
        centreY_[id] = centre[1];
        centreZ_[id] = centre[2];
        faces_.push_back(f);
    }

    void BuildBaseFaces()
    {
        const float t = float((1.0 + std::sqrt(5.0)) / 2.0);
        std::vector<Point3> v = {
            {-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
            {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
        for (Point3 &p : v) p.Normalize();
        const int tri[20][3] = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11},
                                {1, 5, 9}, {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8}, {3, 8, 9},
                                {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
        for (const auto &f : tri) AddFace(v[f[0]], v[f[1]], v[f[2]]);
    }

    int level_;
    int segments_;
    static constexpr int kIcosahedronFaces = 20;
    std::vector<Face> faces_;
    std::vector<double> faceInverse_; // faces_[f].inv row by row at 9 f: TrianglesOfAvx2's gathers
    float centreX_[kIcosahedronFaces] = {}, centreY_[kIcosahedronFaces] = {}, centreZ_[kIcosahedronFaces] = {};
};

} // namespace gaussphere
} // namespace vcg

#endif
