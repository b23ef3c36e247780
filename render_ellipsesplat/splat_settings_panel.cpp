#include "splat_settings_panel.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QSpinBox>

SplatSettingsPanel::SplatSettingsPanel(QWidget *parent) : QDockWidget(tr("Ellipse Splatting"), parent)
{
    const splat::SplatSettings defaults;
    QWidget *body = new QWidget(this);
    QFormLayout *form = new QFormLayout(body);

    mode = new QComboBox(body);
    mode->addItem(tr("Three passes (smooth)"), int(splat::SplatMode::ThreePass));
    mode->addItem(tr("One pass (opaque splats)"), int(splat::SplatMode::OnePassOpaque));
    mode->addItem(tr("Points"), int(splat::SplatMode::Points));
    mode->setToolTip(tr("Three passes blend overlapping splats into a smooth surface; one pass shows each "
                        "splat on its own."));
    form->addRow(tr("Mode"), mode);

    splatScale = new QDoubleSpinBox(body);
    splatScale->setRange(0.1, 5.0);
    splatScale->setSingleStep(0.1);
    splatScale->setValue(defaults.splatScale);
    splatScale->setToolTip(tr("Multiplies both semi-axes of every splat: raise it to close holes."));
    form->addRow(tr("Splat scale"), splatScale);

    depthOffset = new QDoubleSpinBox(body);
    depthOffset->setRange(0.0, 10.0);
    depthOffset->setSingleStep(0.1);
    depthOffset->setValue(defaults.depthOffsetFactor);
    depthOffset->setToolTip(tr("Depth tolerance ε of the blending, in units of each splat's major semi-axis: "
                               "splats closer than ε to the visible surface are blended into it."));
    form->addRow(tr("Depth offset ε (× splat size)"), depthOffset);

    neighbourCount = new QSpinBox(body);
    neighbourCount->setRange(1, 64);
    neighbourCount->setValue(splat::kDefaultSplatNeighbours);
    neighbourCount->setToolTip(tr("For layers without ellipse attributes or radii: a point's circular splat "
                                  "reaches its k-th nearest neighbour."));
    form->addRow(tr("Neighbours k for circles"), neighbourCount);

    cullBackFaces = new QCheckBox(body);
    cullBackFaces->setChecked(defaults.cullBackFaces);
    cullBackFaces->setToolTip(tr("Skip splats facing away; turn off for point sets whose normals are not "
                                 "consistently oriented."));
    form->addRow(tr("Cull back faces"), cullBackFaces);

    fittedPositions = new QCheckBox(body);
    fittedPositions->setChecked(false);
    fittedPositions->setToolTip(tr("Surfels the resampler fitted to their blended surface (attribute "
                                   "SurfelFitOffset) are drawn on the sampled surface, at P - offset N: splats "
                                   "blend shading, not positions. Tick to draw them where they stand (P), e.g. "
                                   "after the layer's normals were flipped or recomputed."));
    form->addRow(tr("Draw at fitted positions"), fittedPositions);

    setWidget(body);
    setAllowedAreas(Qt::NoDockWidgetArea);
    setFloating(true);

    connect(mode, QOverload<int>::of(&QComboBox::currentIndexChanged), this, &SplatSettingsPanel::changed);
    connect(splatScale, QOverload<double>::of(&QDoubleSpinBox::valueChanged), this, &SplatSettingsPanel::changed);
    connect(depthOffset, QOverload<double>::of(&QDoubleSpinBox::valueChanged), this, &SplatSettingsPanel::changed);
    connect(neighbourCount, QOverload<int>::of(&QSpinBox::valueChanged), this, &SplatSettingsPanel::changed);
    connect(cullBackFaces, &QCheckBox::toggled, this, &SplatSettingsPanel::changed);
    connect(fittedPositions, &QCheckBox::toggled, this, &SplatSettingsPanel::changed);
}

splat::SplatSettings SplatSettingsPanel::settings() const
{
    splat::SplatSettings s;
    s.mode = splat::SplatMode(mode->currentData().toInt());
    s.splatScale = float(splatScale->value());
    s.depthOffsetFactor = float(depthOffset->value());
    s.cullBackFaces = cullBackFaces->isChecked();
    return s;
}

int SplatSettingsPanel::neighbours() const
{
    return neighbourCount->value();
}

bool SplatSettingsPanel::atFittedPositions() const
{
    return fittedPositions->isChecked();
}
