// filter_run MESH "FILTER NAME" PLUGIN...: runs a filter the way MeshLab 2022.02 / 2025.07 does,
// without a GUI or GL context. Loads the plugin files through the host's PluginManager (an IO
// plugin able to read MESH among them, e.g. the host's io_base), opens MESH into a MeshDocument
// with the host's own loader, applies the filter named FILTER NAME with the defaults of its
// initParameterList to the current layer, then prints the document's log and every layer:
// label, vertex count, per-vertex attributes. Exit status 1 when a plugin is refused, the
// filter is not found, it throws, or it adds no layer.
#include <common/globals.h>
#include <common/mlexception.h>
#include <common/plugins/plugin_manager.h>
#include <common/utilities/load_save.h>

#include <QApplication>
#include <QElapsedTimer>
#include <QFileInfo>
#include <iostream>

static std::string str(const QString& s) { return s.toStdString(); }

int main(int argc, char** argv)
{
	if (argc < 4) {
		std::cerr << "usage: filter_run MESH \"FILTER NAME\" PLUGIN...\n";
		return 2;
	}
	QApplication app(argc, argv);
	PluginManager& pm = meshlab::pluginManagerInstance();
	for (int i = 3; i < argc; ++i) {
		const QString file = QFileInfo(QString::fromLocal8Bit(argv[i])).absoluteFilePath();
		try {
			pm.loadPlugin(file);
		}
		catch (const MLException& e) {
			std::cout << "refused " << str(file) << ": " << e.what() << "\n";
			return 1;
		}
	}
	const QString filterName = QString::fromLocal8Bit(argv[2]);
	FilterPlugin* plugin = nullptr;
	QAction* action = nullptr;
	for (FilterPlugin* fp : pm.filterPluginIterator())
		for (QAction* a : fp->actions())
			if (fp->filterName(a) == filterName) {
				plugin = fp;
				action = a;
			}
	if (action == nullptr) {
		std::cout << "no filter named \"" << str(filterName) << "\"\n";
		return 1;
	}

	MeshDocument md;
	int status = 0;
	try {
		QElapsedTimer timer;
		timer.start();
		meshlab::loadMeshWithStandardParameters(QString::fromLocal8Bit(argv[1]), md);
		std::cout << "loaded " << argv[1] << ": " << md.mm()->cm.vn << " vertices in "
				  << timer.elapsed() << " ms\n";
		const RichParameterList par = plugin->initParameterList(action, md);
		std::cout << "filter \"" << str(filterName) << "\" (python " << str(plugin->pythonFilterName(action))
				  << "), " << par.size() << " parameters, requiresGLContext " << plugin->requiresGLContext(action)
				  << "\n";
		plugin->setLog(&md.Log);
		unsigned int postConditionMask = plugin->postCondition(action);
		const unsigned int layersBefore = md.meshNumber();
		timer.restart();
		plugin->applyFilter(action, par, md, postConditionMask, nullptr);
		std::cout << "applyFilter returned after " << timer.elapsed() << " ms\n";
		if (md.meshNumber() == layersBefore) {
			std::cout << "the filter added no layer\n";
			status = 1;
		}
	}
	catch (const MLException& e) {
		std::cout << "MLException: " << e.what() << "\n";
		status = 1;
	}
	for (const std::pair<int, QString>& line : md.Log.logStringList())
		std::cout << "log " << line.first << ": " << str(line.second) << "\n";
	for (const MeshModel& m : md.meshIterator()) {
		std::cout << "layer " << m.id() << " \"" << str(m.label()) << "\": " << m.cm.vn << " vertices,"
				  << (&m == md.mm() ? " current," : "") << " per-vertex attributes";
		for (const auto& attribute : m.cm.vert_attr)
			std::cout << " " << attribute._name;
		std::cout << "\n";
	}
	return status;
}
