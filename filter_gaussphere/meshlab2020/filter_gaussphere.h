// MeshLab 2020.09 filter plugin (MeshFilterInterface): Gaussian Sphere Feature-Sensitive
// Resampling and Gaussian Sphere Resampling for Surface Reconstruction. A thin adapter: what
// every host shares is in ../resample_layer.h; the algorithm is vcg_ext/gaussphere/resampling.h.
#ifndef FILTER_GAUSSPHERE_H
#define FILTER_GAUSSPHERE_H

#include <common/interfaces.h>

class FilterGaussSpherePlugin : public QObject, public MeshFilterInterface
{
    Q_OBJECT
    MESHLAB_PLUGIN_IID_EXPORTER(MESH_FILTER_INTERFACE_IID)
    Q_INTERFACES(MeshFilterInterface)

public:
    // In the order of gaussphere_filter::FilterOf.
    enum { FP_GAUSSPHERE_RESAMPLING, FP_GAUSSPHERE_RECONSTRUCTION };

    FilterGaussSpherePlugin();

    QString pluginName() const override;
    QString filterName(FilterIDType filter) const override;
    QString filterInfo(FilterIDType filter) const override;
    FilterClass getClass(QAction *) override;
    FILTER_ARITY filterArity(QAction *) const override;
    int getPreConditions(QAction *) const override;
    int postCondition(QAction *) const override;
    void initParameterSet(QAction *, MeshModel &, RichParameterList &par) override;
    bool applyFilter(QAction *filter, MeshDocument &md, const RichParameterList &par, vcg::CallBackPos *cb) override;
};

#endif
