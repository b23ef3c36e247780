// MeshLab 2021.05+ filter plugin (FilterPlugin; built against 2022.02 and 2025.07): Gaussian
// Sphere Feature-Sensitive Resampling and Gaussian Sphere Resampling for Surface Reconstruction.
// A thin adapter: what every host shares is in ../resample_layer.h; the algorithm is
// vcg_ext/gaussphere/resampling.h.
#ifndef FILTER_GAUSSPHERE_H
#define FILTER_GAUSSPHERE_H

#include <common/plugins/interfaces/filter_plugin.h>

class FilterGaussSpherePlugin : public QObject, public FilterPlugin
{
    Q_OBJECT
    MESHLAB_PLUGIN_IID_EXPORTER(FILTER_PLUGIN_IID)
    Q_INTERFACES(FilterPlugin)

public:
    // In the order of gaussphere_filter::FilterOf.
    enum { FP_GAUSSPHERE_RESAMPLING, FP_GAUSSPHERE_RECONSTRUCTION };

    FilterGaussSpherePlugin();

    QString pluginName() const override;
    QString filterName(ActionIDType filter) const override;
    QString pythonFilterName(ActionIDType filter) const override;
    QString filterInfo(ActionIDType filter) const override;
    FilterClass getClass(const QAction *) const override;
    FilterArity filterArity(const QAction *) const override;
    bool requiresGLContext(const QAction *) const override;
    int getPreConditions(const QAction *) const override;
    int postCondition(const QAction *) const override;
    RichParameterList initParameterList(const QAction *, const MeshModel &) override;
    std::map<std::string, QVariant> applyFilter(const QAction *filter, const RichParameterList &par, MeshDocument &md,
                                                unsigned int &postConditionMask, vcg::CallBackPos *cb) override;
};

#endif
