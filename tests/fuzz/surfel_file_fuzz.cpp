// libFuzzer target: the .surfel reader (io_surfel/surfel_file.h) on arbitrary bytes. The
// reader must either refuse the input with a reason or accept it; whatever it accepts must
// round-trip through the writer: written, then read back, every record returns bit for bit
// (NaNs included, hence no operator==).
#include <surfel_file.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

namespace {

void check(bool condition, const char *what)
{
    if (condition) return;
    std::fprintf(stderr, "surfel_file_fuzz: %s\n", what);
    std::abort();
}

template <class T>
bool sameBits(const T &a, const T &b) { return std::memcmp(&a, &b, sizeof a) == 0; }

bool sameBits(const surfel_io::SurfelRecord &a, const surfel_io::SurfelRecord &b)
{
    return sameBits(a.position, b.position) && sameBits(a.normal, b.normal) && sameBits(a.radius, b.radius) &&
           sameBits(a.majorAxis, b.majorAxis) && sameBits(a.minorAxis, b.minorAxis) &&
           sameBits(a.quality, b.quality) && sameBits(a.blendScale, b.blendScale) &&
           sameBits(a.fitOffset, b.fitOffset) && sameBits(a.color, b.color);
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
    std::istringstream in(std::string(reinterpret_cast<const char *>(data), size));
    std::vector<surfel_io::SurfelRecord> surfels;
    std::string error;
    if (!surfel_io::readSurfels(in, surfels, error)) {
        check(surfels.empty(), "a refused file left surfels behind");
        check(!error.empty(), "a refused file without a reason");
        return 0;
    }

    std::ostringstream out;
    check(surfel_io::writeSurfels(out, surfels, error), "cannot write what was read");
    std::istringstream written(out.str());
    std::vector<surfel_io::SurfelRecord> again;
    check(surfel_io::readSurfels(written, again, error), "cannot read what was written");
    check(again.size() == surfels.size(), "the written file holds another number of surfels");
    for (std::size_t i = 0; i < surfels.size(); ++i)
        check(sameBits(again[i], surfels[i]), "a surfel changed through writing and reading");
    return 0;
}
