// What gsresample's output keeps of its input (tools/gsresample/ply_input.h, double_point_mesh.h):
// double-precision coordinates far from the origin (georeferenced scans) are read near it, so the
// result does not depend on where the model lies, and written back in double; float coordinates
// that far are reported as coarse; vertex colours become each surfel's mean colour.
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include <tools/gsresample/ply_input.h>

#include <wrap/io_trimesh/export_ply.h>
#include <wrap/io_trimesh/import_ply.h>

using gsresample::DoublePointMesh;
using vcg::gaussphere::OrientedPointMesh;

namespace {

// A UTM position: easting, northing, height in metres. Floats there step by 0.25 m and more;
// the bunny is 0.26 m across.
const vcg::Point3d kFar(500000, 4000000, 100);

class GsresampleOutput : public ::testing::Test
{
protected:
    void SetUp() override
    {
        folder_ = ::testing::TempDir() + "gsresample_output_XXXXXX";
        ASSERT_NE(::mkdtemp(&folder_[0]), nullptr);
        std::string error;
        ASSERT_TRUE(gsresample::ReadOrientedPoints(std::string(SAMPLE_DIR) + "/bunny.ply", bunny_, error)) << error;
    }

    void TearDown() override { std::system(("rm -rf '" + folder_ + "'").c_str()); }

    std::string Path(const std::string &name) const { return folder_ + "/" + name; }

    /// The bunny, each point red left of x = `split` and blue right of it.
    template <class MeshType>
    std::string WriteTwoColours(const std::string &name, float split)
    {
        MeshType mesh;
        auto vi = vcg::tri::Allocator<MeshType>::AddVertices(mesh, bunny_.vert.size());
        for (const auto &v : bunny_.vert) {
            vi->P() = MeshType::CoordType::Construct(v.cP());
            vi->N() = MeshType::CoordType::Construct(v.cN());
            vi->C() = v.cP()[0] < split ? vcg::Color4b::Red : vcg::Color4b::Blue;
            ++vi;
        }
        return Save(mesh, name, vcg::tri::io::Mask::IOM_VERTCOLOR);
    }

    /// The bunny moved by `offset`, in double (exactly: its floats and these offsets need fewer
    /// than 53 bits together, but for a few coordinates very near zero).
    std::string WriteDouble(const std::string &name, const vcg::Point3d &offset)
    {
        DoublePointMesh mesh;
        auto vi = vcg::tri::Allocator<DoublePointMesh>::AddVertices(mesh, bunny_.vert.size());
        for (const auto &v : bunny_.vert) {
            vi->P() = vcg::Point3d::Construct(v.cP()) + offset;
            vi->N() = vcg::Point3d::Construct(v.cN());
            ++vi;
        }
        return Save(mesh, name);
    }

    /// The bunny moved by `offset` in float, as a float-only reader or host holds it.
    std::string WriteFloat(const std::string &name, const vcg::Point3d &offset)
    {
        OrientedPointMesh mesh;
        auto vi = vcg::tri::Allocator<OrientedPointMesh>::AddVertices(mesh, bunny_.vert.size());
        for (const auto &v : bunny_.vert) {
            vi->P() = vcg::Point3f::Construct(vcg::Point3d::Construct(v.cP()) + offset);
            vi->N() = v.cN();
            ++vi;
        }
        return Save(mesh, name);
    }

    /// Runs gsresample INPUT OUTPUT; returns its exit status, its standard error in `err`.
    int Resample(const std::string &input, const std::string &output, std::string &err)
    {
        const std::string errPath = output + ".stderr";
        const std::string command = std::string(GSRESAMPLE) + " '" + input + "' '" + output + "' > /dev/null 2> '" +
                                    errPath + "'";
        const int status = std::system(command.c_str());
        std::ifstream in(errPath);
        std::stringstream text;
        text << in.rdbuf();
        err = text.str();
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    }

    static std::string HeaderOf(const std::string &path)
    {
        std::ifstream in(path, std::ios::binary);
        std::string header, line;
        while (std::getline(in, line) && line != "end_header") header += line + "\n";
        return header;
    }

    template <class MeshType>
    std::string Save(MeshType &mesh, const std::string &name, int extraMask = 0)
    {
        const int mask = vcg::tri::io::Mask::IOM_VERTNORMAL | extraMask;
        EXPECT_EQ(vcg::tri::io::ExporterPLY<MeshType>::Save(mesh, Path(name).c_str(), mask, true), 0);
        return Path(name);
    }

    std::string folder_;
    OrientedPointMesh bunny_;
};

TEST_F(GsresampleOutput, DoubleCoordinatesAreReadNearTheOriginAtFullPrecision)
{
    const std::string input = WriteDouble("far.ply", kFar);
    OrientedPointMesh mesh;
    gsresample::InputInfo info;
    std::string error;
    ASSERT_TRUE(gsresample::ReadOrientedPoints(input, mesh, error, &info)) << error;
    ASSERT_TRUE(info.doubleCoordinates);
    vcg::Box3d box;
    for (const auto &v : bunny_.vert) box.Add(vcg::Point3d::Construct(v.cP()));
    EXPECT_LT((info.origin - (box.Center() + kFar)).Norm(), 1e-9);
    ASSERT_EQ(mesh.vert.size(), bunny_.vert.size());
    for (size_t i = 0; i < mesh.vert.size(); ++i) {
        const vcg::Point3d expected = vcg::Point3d::Construct(bunny_.vert[i].cP()) - box.Center();
        ASSERT_LT((vcg::Point3d::Construct(mesh.vert[i].cP()) - expected).Norm(), 1e-7) << "vertex " << i;
    }
    // Without an InputInfo to report the move, double coordinates become float as they are.
    OrientedPointMesh plain;
    ASSERT_TRUE(gsresample::ReadOrientedPoints(input, plain, error)) << error;
    EXPECT_EQ(plain.vert[0].cP(), vcg::Point3f::Construct(vcg::Point3d::Construct(bunny_.vert[0].cP()) + kFar));
}

TEST_F(GsresampleOutput, DoubleCoordinatesGiveTheSameSurfelsWhereverTheModelLies)
{
    std::string err;
    ASSERT_EQ(Resample(WriteDouble("near.ply", vcg::Point3d(0, 0, 0)), Path("near_out.ply"), err), 0) << err;
    EXPECT_EQ(err, "");
    ASSERT_EQ(Resample(WriteDouble("far.ply", kFar), Path("far_out.ply"), err), 0) << err;
    EXPECT_EQ(err, "");
    EXPECT_NE(HeaderOf(Path("far_out.ply")).find("property double x\nproperty double y\nproperty double z\n"),
              std::string::npos);
    DoublePointMesh near, far;
    int mask = 0;
    ASSERT_EQ(vcg::tri::io::ImporterPLY<DoublePointMesh>::Open(near, Path("near_out.ply").c_str(), mask), 0);
    ASSERT_EQ(vcg::tri::io::ImporterPLY<DoublePointMesh>::Open(far, Path("far_out.ply").c_str(), mask), 0);
    ASSERT_GT(near.vert.size(), bunny_.vert.size() / 5);
    ASSERT_EQ(far.vert.size(), near.vert.size());
    for (size_t i = 0; i < near.vert.size(); ++i) {
        ASSERT_LT((far.vert[i].cP() - kFar - near.vert[i].cP()).Norm(), 1e-8) << "surfel " << i;
        ASSERT_LT((far.vert[i].cN() - near.vert[i].cN()).Norm(), 1e-6) << "surfel " << i;
        ASSERT_EQ(far.vert[i].cQ(), near.vert[i].cQ()) << "surfel " << i;
    }
}

TEST_F(GsresampleOutput, DoubleCoordinatesFloatCoordinatesThatFarAreReportedCoarse)
{
    std::string err;
    ASSERT_EQ(Resample(WriteFloat("far_float.ply", kFar), Path("far_float_out.ply"), err), 0) << err;
    EXPECT_NE(err.find("gsresample: warning: the points lie up to 4000000 units from the origin"), std::string::npos)
        << err;
    EXPECT_NE(err.find("held in steps of 0.25"), std::string::npos) << err;
}

TEST_F(GsresampleOutput, DoubleCoordinatesSurfelOutputWarnsOfItsFloatCoordinates)
{
    std::string err;
    ASSERT_EQ(Resample(WriteDouble("far.ply", kFar), Path("far_out.surfel"), err), 0) << err;
    EXPECT_NE(err.find("the .surfel format holds float coordinates"), std::string::npos) << err;
    ASSERT_EQ(Resample(WriteDouble("near.ply", vcg::Point3d(0, 0, 0)), Path("near_out.surfel"), err), 0) << err;
    EXPECT_EQ(err, "");
}

// Each surfel takes the mean colour of its points: on a bunny red on one side of a plane and blue
// on the other, every surfel is a mix of the two, those away from the plane pure, in float and in
// double input alike; an input without colours gives an output without them.
TEST_F(GsresampleOutput, ColoursAreTheMeanOfTheSurfelsPoints)
{
    const float split = -0.02f; // through the bunny's middle
    for (const std::string &input : {WriteTwoColours<OrientedPointMesh>("coloured.ply", split),
                                     WriteTwoColours<DoublePointMesh>("coloured_double.ply", split)}) {
        std::string err;
        const std::string output = input + ".out.ply";
        ASSERT_EQ(Resample(input, output, err), 0) << err;
        EXPECT_NE(HeaderOf(output).find("property uchar red\nproperty uchar green\nproperty uchar blue\n"),
                  std::string::npos) << HeaderOf(output);
        OrientedPointMesh out;
        int mask = 0;
        ASSERT_EQ(vcg::tri::io::ImporterPLY<OrientedPointMesh>::Open(out, output.c_str(), mask), 0);
        ASSERT_TRUE(mask & vcg::tri::io::Mask::IOM_VERTCOLOR);
        int pureRed = 0, pureBlue = 0;
        for (const auto &v : out.vert) {
            const vcg::Color4b c = v.cC();
            ASSERT_EQ(int(c[1]), 0);
            ASSERT_NEAR(int(c[0]) + int(c[2]), 255, 1) << "a mix of red and blue (each mean rounded)";
            const bool red = c[0] == 255, blue = c[2] == 255;
            if (std::abs(v.cP()[0] - split) > 0.01f) ASSERT_TRUE(red || blue) << "away from the split";
            pureRed += red;
            pureBlue += blue;
        }
        EXPECT_GT(pureRed, int(out.vert.size()) / 4);
        EXPECT_GT(pureBlue, int(out.vert.size()) / 4);
    }
    std::string err;
    ASSERT_EQ(Resample(std::string(SAMPLE_DIR) + "/bunny.ply", Path("plain_out.ply"), err), 0) << err;
    EXPECT_EQ(HeaderOf(Path("plain_out.ply")).find("red"), std::string::npos);
}

} // namespace
