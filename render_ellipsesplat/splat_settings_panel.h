#pragma once
// The floating panel that comes up with "Ellipse Splatting": splat mode, splat scale, ε, the
// neighbour count used to size circular splats of layers without ellipse attributes, and where
// surfels fitted to their blend are drawn.

#include "ellipse_splat_renderer.h"

#include <QDockWidget>

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QSpinBox;

class SplatSettingsPanel : public QDockWidget
{
    Q_OBJECT
public:
    explicit SplatSettingsPanel(QWidget *parent);

    splat::SplatSettings settings() const;
    int neighbours() const;
    /// Whether surfels with a SurfelFitOffset are drawn where the resampler fitted them (P)
    /// rather than on the sampled surface (P - offset N, the default).
    bool atFittedPositions() const;

signals:
    void changed();

private:
    QComboBox *mode;
    QDoubleSpinBox *splatScale;
    QDoubleSpinBox *depthOffset;
    QSpinBox *neighbourCount;
    QCheckBox *cullBackFaces;
    QCheckBox *fittedPositions;
};
