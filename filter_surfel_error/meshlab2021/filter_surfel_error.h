// MeshLab 2021.05+ filter plugin (FilterPlugin; built against 2022.02 and 2025.07): Surfel
// Approximation Error. A thin adapter: what every host shares is in ../surfel_error_layer.h; the
// metric is vcg_ext/surfel_error/surfel_error.h.
#ifndef FILTER_SURFEL_ERROR_H
#define FILTER_SURFEL_ERROR_H

#include <common/plugins/interfaces/filter_plugin.h>

class FilterSurfelErrorPlugin : public QObject, public FilterPlugin
{
    Q_OBJECT
    MESHLAB_PLUGIN_IID_EXPORTER(FILTER_PLUGIN_IID)
    Q_INTERFACES(FilterPlugin)

public:
    enum { FP_SURFEL_APPROXIMATION_ERROR };

    FilterSurfelErrorPlugin();

    QString pluginName() const override;
    QString filterName(ActionIDType filter) const override;
    QString pythonFilterName(ActionIDType filter) const override;
    QString filterInfo(ActionIDType filter) const override;
    FilterClass getClass(const QAction *) const override;
    FilterArity filterArity(const QAction *) const override;
    bool requiresGLContext(const QAction *) const override;
    int getPreConditions(const QAction *) const override;
    int postCondition(const QAction *) const override;
    RichParameterList initParameterList(const QAction *, const MeshDocument &md) override;
    std::map<std::string, QVariant> applyFilter(const QAction *filter, const RichParameterList &par, MeshDocument &md,
                                                unsigned int &postConditionMask, vcg::CallBackPos *cb) override;
};

#endif
