#pragma once
// The render plugin's MeshLab glue that is the same for every host (2020.09, 2022.02, 2025.07):
// what "Ellipse Splatting" does with the document, each view (GLArea), the settings panel and
// the splats of each layer. It does not log: its functions return the messages, and each host's
// adapter (meshlab2020/, meshlab2021/) logs them its host's way, as warnings.

#include "ellipse_splat_renderer.h"

#include <QPointer>
#include <QString>

#include <cstdint>
#include <map>
#include <memory>
#include <set>
#include <vector>

class GLArea;
class MeshDocument;
class MeshModel;
class SplatSettingsPanel;

namespace splat {

QString pluginName();
QString actionName();
QString actionToolTip();

// Messages for the log, in order.
using LogTexts = std::vector<QString>;

class SplatViews
{
public:
    SplatViews();
    ~SplatViews();
    SplatViews(const SplatViews &) = delete;
    SplatViews &operator=(const SplatViews &) = delete;

    // The mode is switched on in `view`: its renderer is made (shaders compiled) and the
    // settings panel shown. supported() tells whether that worked.
    LogTexts init(GLArea *view);
    bool supported() const { return isSupported; }
    // Draws the visible layers of `document` in `view`: oriented point sets as splats, the
    // others through MeshLab's own drawing.
    LogTexts render(MeshDocument &document, GLArea *view);
    // The mode is switched off in `view`: its GL objects are deleted, and the panel with the
    // last view.
    void finalize(GLArea *view);

private:
    struct CachedCloud
    {
        std::uint64_t fingerprint;
        std::unique_ptr<SplatCloud> cloud;
    };
    // GL objects live in one context: each view (GLArea) that uses the plugin has its own.
    struct ViewResources
    {
        std::unique_ptr<EllipseSplatRenderer> renderer;
        std::map<int, CachedCloud> clouds; // by layer id
    };

    const SplatCloud *cloudOf(ViewResources &resources, const MeshModel &layer, GLArea *view, LogTexts &log);
    void logOnce(const MeshModel &layer, const QString &message, LogTexts &log);

    bool isSupported = false;
    std::map<GLArea *, ViewResources> views;
    QPointer<SplatSettingsPanel> panel; // null once deleted, also by its parent window
    std::set<std::pair<int, QString>> loggedMessages; // (layer id, or -1 for the whole view; message) logged
};

} // namespace splat
