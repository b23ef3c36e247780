// io_run MESH OUT_DIR PLUGIN...: the .surfel round trip and the surfel error filter in MeshLab
// 2022.02 / 2025.07, without a GUI or GL context, through the host's PluginManager (the plugins
// among PLUGIN...: an IO plugin reading MESH, filter_gaussphere, io_surfel, filter_surfel_error):
//  1. opens MESH with the host's loader and resamples it (the filter's dialog defaults);
//  2. saves the new layer as OUT_DIR/resampled.surfel with the host's saver (the plugin
//     PluginManager::outputMeshPlugin picks for the extension, its mask and save parameters);
//  3. opens that file with the host's loader (inputMeshPlugin by extension) into a new layer and
//     compares it with the saved one: vertex count, positions, normals, radii, quality, colour,
//     and the per-vertex attributes EllipseMajorAxis, EllipseMinorAxis, SurfelFitOffset,
//     SurfelBlendScale (presence and values, exactly);
//  4. hostile files made from it (truncated, a NaN position, an infinite normal, not a PLY) and
//     a layer with a NaN position to save: each must throw MLException whose text is one
//     printable line with the reader's reason, the open must add no layer, the save no file;
//  5. runs "Surfel Approximation Error" on the resampled layer, then on the reopened one, against
//     MESH: both log the same figures.
// Prints "check NAME: ok|FAIL ..." lines, the log and the layers; exit status 1 when a check fails.
#include "probe_support.h"

#include <common/utilities/load_save.h>
#include <vcg_ext/surfel/surfel_attributes.h>

#include <QApplication>
#include <QDir>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <regex>
#include <vector>

namespace {

int failures = 0;

bool check(bool ok, const std::string& name, const std::string& detail)
{
	std::cout << "check " << name << ": " << (ok ? "ok" : "FAIL") << ", " << detail << "\n";
	failures += ok ? 0 : 1;
	return ok;
}

const QString kFormat = "surfel";

// Values of a per-vertex attribute (`present` false when the layer has none of that name).
template <class T>
std::vector<T> attributeValues(CMeshO& m, const char* name, bool& present)
{
	auto handle = vcg::tri::Allocator<CMeshO>::FindPerVertexAttribute<T>(m, name);
	present = vcg::tri::Allocator<CMeshO>::IsValidHandle(m, handle);
	std::vector<T> values;
	for (size_t i = 0; present && i < m.vert.size(); ++i)
		values.push_back(handle[i]);
	return values;
}

template <class T>
void compareAttribute(CMeshO& saved, CMeshO& reopened, const char* name)
{
	bool savedHas = false, reopenedHas = false;
	const std::vector<T> a = attributeValues<T>(saved, name, savedHas);
	const std::vector<T> b = attributeValues<T>(reopened, name, reopenedHas);
	size_t differ = 0;
	for (size_t i = 0; i < a.size() && i < b.size(); ++i)
		differ += a[i] == b[i] ? 0 : 1;
	check(savedHas && reopenedHas && a.size() == b.size() && differ == 0, std::string("attribute ") + name,
		  std::string("saved ") + (savedHas ? "has it" : "lacks it") + ", reopened " +
			  (reopenedHas ? "has it" : "lacks it") + ", " + std::to_string(differ) + " of " +
			  std::to_string(a.size()) + " values differ");
}

// Vertices whose component `get` differs between the layers (same vertex count).
template <class Get>
void compareComponent(const CMeshO& saved, const CMeshO& reopened, const char* name, Get get)
{
	size_t differ = 0;
	for (size_t i = 0; i < saved.vert.size(); ++i)
		differ += get(saved.vert[i]) == get(reopened.vert[i]) ? 0 : 1;
	check(differ == 0, name, std::to_string(differ) + " of " + std::to_string(saved.vert.size()) + " differ");
}

void compareLayers(MeshModel& saved, MeshModel& reopened)
{
	CMeshO &a = saved.cm, &b = reopened.cm;
	if (!check(a.vn == b.vn && a.vert.size() == b.vert.size(), "vertex count",
			   "saved " + std::to_string(a.vn) + ", reopened " + std::to_string(b.vn)))
		return;
	compareComponent(a, b, "positions", [](const CVertexO& v) { return v.cP(); });
	compareComponent(a, b, "normals", [](const CVertexO& v) { return v.cN(); });
	compareComponent(a, b, "radii", [](const CVertexO& v) { return v.cR(); });
	compareComponent(a, b, "quality", [](const CVertexO& v) { return v.cQ(); });
	compareComponent(a, b, "colour", [](const CVertexO& v) { return v.cC(); });
	compareAttribute<Point3m>(a, b, vcg::gaussphere::kMajorAxisAttribute);
	compareAttribute<Point3m>(a, b, vcg::gaussphere::kMinorAxisAttribute);
	compareAttribute<float>(a, b, vcg::gaussphere::kFitOffsetAttribute);
	compareAttribute<float>(a, b, vcg::gaussphere::kBlendScaleAttribute);
}

// `text` is one line of printable ASCII.
bool oneLine(const std::string& text)
{
	for (char c : text)
		if (c < 0x20 || c > 0x7e)
			return false;
	return !text.empty();
}

// Runs `attempt`, which must throw MLException whose text is one line holding each of `parts`.
template <class Attempt>
void expectRefusal(const std::string& name, const std::vector<std::string>& parts, Attempt attempt)
{
	try {
		attempt();
		check(false, name, "no exception");
	}
	catch (const MLException& e) {
		const std::string what = e.what();
		bool ok = oneLine(what);
		for (const std::string& part : parts)
			ok = ok && what.find(part) != std::string::npos;
		check(ok, name, "MLException: " + what);
	}
}

std::vector<char> readBytes(const QString& file)
{
	std::ifstream in(file.toStdString(), std::ios::binary);
	return std::vector<char>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void writeBytes(const QString& file, const std::vector<char>& bytes)
{
	std::ofstream(file.toStdString(), std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

// `good` with float PROPERTY of RECORD (68 bytes each after the header) set to the
// little-endian `bits`.
std::vector<char> withFloat(std::vector<char> good, size_t record, size_t property, std::uint32_t bits)
{
	const std::string end = "end_header\n";
	const size_t data = std::string(good.begin(), good.end()).find(end) + end.size();
	for (int i = 0; i < 4; ++i)
		good.at(data + record * 68 + property * 4 + i) = char(bits >> (8 * i));
	return good;
}

// Hostile .surfel files made from the good one, each opened with the host's loader, and a
// layer with a NaN position saved: every one refused with its reason.
void hostileFiles(const QString& good, const QDir& out, int surfels)
{
	const std::vector<char> bytes = readBytes(good);
	const struct
	{
		const char* name;
		std::vector<char> bytes;
		std::string reason;
	} cases[] = {
		{"truncated", std::vector<char>(bytes.begin(), bytes.end() - 7),
		 "truncated file: the header announces " + std::to_string(surfels) + " surfels, the data holds " +
			 std::to_string(surfels - 1)},
		{"nan_position", withFloat(bytes, 7, 0, 0x7fc00000u), "surfel 7 has a non-finite x (nan)"},
		{"inf_normal", withFloat(bytes, 0, 5, 0x7f800000u), "surfel 0 has a non-finite nz (inf)"},
		{"not_ply", std::vector<char>(5000, '\252'), "not a PLY file"},
	};
	for (const auto& c : cases) {
		const QString file = out.filePath(QString(c.name) + ".surfel");
		writeBytes(file, c.bytes);
		MeshDocument md;
		const std::string name = std::string("hostile open ") + c.name;
		expectRefusal(name, {"IOSurfel: cannot load '", c.reason},
					  [&] { meshlab::loadMeshWithStandardParameters(file, md); });
		check(md.meshNumber() == 0, name + " adds no layer", std::to_string(md.meshNumber()) + " layer(s)");
	}
	const QString nanSave = out.filePath("nan_layer.surfel");
	QFile::remove(nanSave);
	expectRefusal("hostile save nan_layer", {"IOSurfel: cannot save '", "surfel 1 has a non-finite y (nan)"}, [&] {
		MeshDocument md;
		MeshModel* m = md.addNewMesh("", "nan layer");
		auto v = vcg::tri::Allocator<CMeshO>::AddVertices(m->cm, 3);
		v[1].P() = Point3m(1, std::nanf(""), 0);
		meshlab::saveMeshWithStandardParameters(nanSave, *m);
	});
	check(!QFile::exists(nanSave), "hostile save leaves no file", str(nanSave));
}

// The figures of the surfel error filter's log: its lines from `first` on, the layer names and
// the time left out.
std::string errorFigures(const MeshDocument& md, int first)
{
	const std::regex names("'[^']*'"), time("; [0-9.]+ s$");
	std::string figures;
	int index = 0;
	for (const std::pair<int, QString>& line : md.Log.logStringList()) {
		const std::string text = str(line.second);
		if (index++ >= first && text.compare(0, 12, "Surfel error") == 0)
			figures += std::regex_replace(std::regex_replace(text, names, "''"), time, "") + "\n";
	}
	return figures;
}

// The surfel error filter on `simplified` (made current) against the layer with SurfelIndex:
// the figures it logged.
std::string measureError(const FilterAction& filter, MeshDocument& md, const MeshModel& simplified, int& printed)
{
	md.setCurrentMesh(simplified.id());
	const int first = md.Log.logStringList().size();
	applyWithDefaults(filter, md);
	printNewLog(md, printed);
	const std::string figures = errorFigures(md, first);
	check(!figures.empty(), "error filter on \"" + str(simplified.label()) + "\"", "logged its figures");
	return figures;
}

// Steps 1 to 3 and 5 on `md`; MLException passes through.
void roundTrip(const QString& mesh, const QDir& out, MeshDocument& md, int& printed)
{
	const FilterAction resample = findFilter("Gaussian Sphere Feature-Sensitive Resampling");
	const FilterAction error = findFilter("Surfel Approximation Error");
	const PluginManager& pm = meshlab::pluginManagerInstance();
	const IOPlugin *saver = pm.outputMeshPlugin(kFormat), *opener = pm.inputMeshPlugin(kFormat);
	if (!check(resample.action && error.action, "filters", "resampling and surfel error found") ||
		!check(saver && opener, "io lookup",
			   "." + str(kFormat) + " saved by " + (saver ? str(saver->pluginName()) : "none") + ", opened by " +
				   (opener ? str(opener->pluginName()) : "none")))
		return;
	meshlab::loadMeshWithStandardParameters(mesh, md);
	applyWithDefaults(resample, md);
	printNewLog(md, printed);
	MeshModel& resampled = *md.mm();
	const QString file = out.filePath("resampled.surfel");
	meshlab::saveMeshWithStandardParameters(file, resampled, &md.Log);
	std::cout << "saved " << resampled.cm.vn << " surfels to " << str(file) << ", " << QFileInfo(file).size()
			  << " bytes\n";
	meshlab::loadMeshWithStandardParameters(file, md);
	MeshModel& reopened = *md.mm();
	compareLayers(resampled, reopened);
	hostileFiles(file, out, resampled.cm.vn);
	const std::string first = measureError(error, md, resampled, printed);
	const std::string again = measureError(error, md, reopened, printed);
	check(first == again, "error figures", "the reopened layer's equal the resampled layer's: " + first);
}

} // namespace

int main(int argc, char** argv)
{
	if (argc < 4) {
		std::cerr << "usage: io_run MESH OUT_DIR PLUGIN...\n";
		return 2;
	}
	QApplication app(argc, argv);
	if (!loadPluginFiles(argv + 3, argv + argc))
		return 1;
	const QDir out(QString::fromLocal8Bit(argv[2]));
	MeshDocument md;
	int printed = 0;
	try {
		roundTrip(QString::fromLocal8Bit(argv[1]), out, md, printed);
	}
	catch (const MLException& e) {
		check(false, "no exception", std::string("MLException: ") + e.what());
	}
	printNewLog(md, printed);
	printLayers(md);
	std::cout << (failures == 0 ? "all checks passed\n" : std::to_string(failures) + " check(s) failed\n");
	return failures == 0 ? 0 : 1;
}
