// plugin_probe PLUGIN_OR_DIR...: loads MeshLab plugins with the host's PluginManager
// (libmeshlab-common.so of 2022.02 / 2025.07) and prints, one line each, what was loaded or
// refused and why, then every filter (name, python name, class, GL context), IO format and
// render action of the loaded plugins. Exit status 1 when anything was refused.
#include <common/globals.h>
#include <common/mlapplication.h>
#include <common/mlexception.h>
#include <common/plugins/plugin_manager.h>

#include <QApplication>
#include <QDir>
#include <QFileInfo>
#include <iostream>

static std::string str(const QString& s) { return s.toStdString(); }

int main(int argc, char** argv)
{
	QApplication app(argc, argv);
	PluginManager& pm = meshlab::pluginManagerInstance();
	int status = 0;
	std::cout << "host libmeshlab-common: MeshLab " << str(MeshLabApplication::appVer()) << "\n";
	for (int i = 1; i < argc; ++i) {
		QFileInfo arg(QString::fromLocal8Bit(argv[i]));
		QStringList files;
		if (arg.isDir())
			for (const QFileInfo& f : QDir(arg.absoluteFilePath()).entryInfoList({"*.so"}, QDir::Files))
				files << f.absoluteFilePath();
		else
			files << arg.absoluteFilePath();
		for (const QString& f : files) {
			try {
				MeshLabPlugin* p = pm.loadPlugin(f);
				std::cout << "loaded  " << str(QFileInfo(f).fileName()) << ": " << str(p->pluginName())
						  << " (built for " << p->getMLVersion().first
						  << (p->getMLVersion().second ? ", double" : ", float") << ")\n";
			}
			catch (const MLException& e) {
				std::cout << "refused " << str(QFileInfo(f).fileName()) << ": " << e.what() << "\n";
				status = 1;
			}
		}
	}
	for (FilterPlugin* fp : pm.filterPluginIterator())
		for (QAction* a : fp->actions())
			std::cout << "filter  " << str(fp->pluginName()) << ": \"" << str(fp->filterName(a))
					  << "\" python " << str(fp->pythonFilterName(a)) << " class 0x" << std::hex
					  << int(fp->getClass(a)) << std::dec << " requiresGLContext "
					  << fp->requiresGLContext(a) << "\n";
	for (IOPlugin* io : pm.ioPluginIterator()) {
		std::cout << "io      " << str(io->pluginName()) << ": import";
		for (const FileFormat& f : io->importFormats())
			std::cout << " " << str(f.extensions.join(","));
		std::cout << "; export";
		for (const FileFormat& f : io->exportFormats())
			std::cout << " " << str(f.extensions.join(","));
		std::cout << "\n";
	}
	for (RenderPlugin* rp : pm.renderPluginIterator())
		for (QAction* a : rp->actions())
			std::cout << "render  " << str(rp->pluginName()) << ": \"" << str(a->text()) << "\"\n";
	return status;
}
