// What the host probes filter_run and io_run share: loading plugin files through the host's
// PluginManager, finding a filter by name, running it with its dialog defaults, printing the
// document. MeshLab 2021.05+ API (2022.02, 2025.07).
#ifndef HOSTS_OOT_PROBE_SUPPORT_H
#define HOSTS_OOT_PROBE_SUPPORT_H

#include <common/globals.h>
#include <common/mlexception.h>
#include <common/plugins/plugin_manager.h>

#include <QElapsedTimer>
#include <QFileInfo>
#include <iostream>
#include <string>

inline std::string str(const QString& s) { return s.toStdString(); }

// Loads the plugin files [first, last) with the host's PluginManager; false (and a line
// "refused FILE: reason") when it refuses one.
inline bool loadPluginFiles(char** first, char** last)
{
	for (char** arg = first; arg != last; ++arg) {
		const QString file = QFileInfo(QString::fromLocal8Bit(*arg)).absoluteFilePath();
		try {
			meshlab::pluginManagerInstance().loadPlugin(file);
		}
		catch (const MLException& e) {
			std::cout << "refused " << str(file) << ": " << e.what() << "\n";
			return false;
		}
	}
	return true;
}

struct FilterAction
{
	FilterPlugin* plugin = nullptr;
	QAction* action = nullptr;
};

// The loaded filter named `name` (the last one loaded, as in the GUI); null members, and a
// line saying so, when there is none.
inline FilterAction findFilter(const QString& name)
{
	FilterAction found;
	for (FilterPlugin* fp : meshlab::pluginManagerInstance().filterPluginIterator())
		for (QAction* a : fp->actions())
			if (fp->filterName(a) == name)
				found = {fp, a};
	if (found.action == nullptr)
		std::cout << "no filter named \"" << str(name) << "\"\n";
	return found;
}

// Applies `filter` to `md` with the defaults of its initParameterList, its log into the
// document's, without a GL context, and prints its python name, parameter count and time.
// MLException passes through.
inline void applyWithDefaults(const FilterAction& filter, MeshDocument& md)
{
	const RichParameterList par = filter.plugin->initParameterList(filter.action, md);
	std::cout << "filter \"" << str(filter.plugin->filterName(filter.action)) << "\" (python "
			  << str(filter.plugin->pythonFilterName(filter.action)) << "), " << par.size()
			  << " parameters, requiresGLContext " << filter.plugin->requiresGLContext(filter.action) << "\n";
	filter.plugin->setLog(&md.Log);
	unsigned int postConditionMask = filter.plugin->postCondition(filter.action);
	QElapsedTimer timer;
	timer.start();
	filter.plugin->applyFilter(filter.action, par, md, postConditionMask, nullptr);
	std::cout << "applyFilter returned after " << timer.elapsed() << " ms\n";
}

// The document's log lines not printed yet ("log LEVEL: TEXT"); `printed` counts those printed.
inline void printNewLog(const MeshDocument& md, int& printed)
{
	int index = 0;
	for (const std::pair<int, QString>& line : md.Log.logStringList())
		if (index++ >= printed)
			std::cout << "log " << line.first << ": " << str(line.second) << "\n";
	printed = index;
}

// Every layer: id, label, vertex count, whether current, per-vertex attributes.
inline void printLayers(const MeshDocument& md)
{
	for (const MeshModel& m : md.meshIterator()) {
		std::cout << "layer " << m.id() << " \"" << str(m.label()) << "\": " << m.cm.vn << " vertices,"
				  << (&m == md.mm() ? " current," : "") << " per-vertex attributes";
		for (const auto& attribute : m.cm.vert_attr)
			std::cout << " " << attribute._name;
		std::cout << "\n";
	}
}

#endif
