// MeshLab 2020.09 filter plugin (MeshFilterInterface): Surfel Approximation Error. A thin
// adapter: what every host shares is in ../surfel_error_layer.h; the metric is
// vcg_ext/surfel_error/surfel_error.h.
#ifndef FILTER_SURFEL_ERROR_H
#define FILTER_SURFEL_ERROR_H

#include <common/interfaces.h>

class FilterSurfelErrorPlugin : public QObject, public MeshFilterInterface
{
    Q_OBJECT
    MESHLAB_PLUGIN_IID_EXPORTER(MESH_FILTER_INTERFACE_IID)
    Q_INTERFACES(MeshFilterInterface)

public:
    enum { FP_SURFEL_APPROXIMATION_ERROR };

    FilterSurfelErrorPlugin();

    QString pluginName() const override;
    QString filterName(FilterIDType filter) const override;
    QString filterInfo(FilterIDType filter) const override;
    FilterClass getClass(QAction *) override;
    FILTER_ARITY filterArity(QAction *) const override;
    int getPreConditions(QAction *) const override;
    int postCondition(QAction *) const override;
    void initParameterSet(QAction *, MeshDocument &md, RichParameterList &par) override;
    bool applyFilter(QAction *filter, MeshDocument &md, const RichParameterList &par, vcg::CallBackPos *cb) override;
};

#endif
