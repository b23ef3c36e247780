// filter_run MESH "FILTER NAME" PLUGIN...: runs a filter the way MeshLab 2022.02 / 2025.07 does,
// without a GUI or GL context. Loads the plugin files through the host's PluginManager (an IO
// plugin able to read MESH among them, e.g. the host's io_base), opens MESH into a MeshDocument
// with the host's own loader, applies the filter named FILTER NAME with the defaults of its
// initParameterList to the current layer, then prints the document's log and every layer:
// label, vertex count, per-vertex attributes. Exit status 1 when a plugin is refused, the
// filter is not found, it throws, or it adds no layer.
#include "probe_support.h"

#include <common/utilities/load_save.h>

#include <QApplication>

int main(int argc, char** argv)
{
	if (argc < 4) {
		std::cerr << "usage: filter_run MESH \"FILTER NAME\" PLUGIN...\n";
		return 2;
	}
	QApplication app(argc, argv);
	if (!loadPluginFiles(argv + 3, argv + argc))
		return 1;
	const FilterAction filter = findFilter(QString::fromLocal8Bit(argv[2]));
	if (filter.action == nullptr)
		return 1;

	MeshDocument md;
	int status = 0;
	try {
		QElapsedTimer timer;
		timer.start();
		meshlab::loadMeshWithStandardParameters(QString::fromLocal8Bit(argv[1]), md);
		std::cout << "loaded " << argv[1] << ": " << md.mm()->cm.vn << " vertices in "
				  << timer.elapsed() << " ms\n";
		const unsigned int layersBefore = md.meshNumber();
		applyWithDefaults(filter, md);
		if (md.meshNumber() == layersBefore) {
			std::cout << "the filter added no layer\n";
			status = 1;
		}
	}
	catch (const MLException& e) {
		std::cout << "MLException: " << e.what() << "\n";
		status = 1;
	}
	int printed = 0;
	printNewLog(md, printed);
	printLayers(md);
	return status;
}
