#pragma once
// `glcollide view --input FILE`: a script of input events at given viewer frames, so the viewer's
// interactions can be run and tested without a user (docs/viewer.md, "Input scripts"). GL-free.

#include <filesystem>
#include <string>
#include <vector>

namespace glcollide::viewer {

/// One input event, at the start of viewer frame `frame` (1 = the first frame shown).
struct InputEvent {
    enum class Kind { Key, MouseDown, MouseMove, MouseUp, Scroll, Open, Screenshot };
    Kind kind = Kind::Key;
    int frame = 1;
    int key = 0;         ///< Key: a GLFW key code
    int button = 0;      ///< Mouse*: GLFW_MOUSE_BUTTON_LEFT, _RIGHT or _MIDDLE
    int mods = 0;        ///< GLFW_MOD_CONTROL / GLFW_MOD_SHIFT
    double x = 0.0;      ///< Mouse*, Scroll: window pixels from the left
    double y = 0.0;      ///< ... from the top
    double scroll = 0.0; ///< Scroll: wheel steps (positive: away from the user, zooms in)
    std::string path;    ///< Open: a scene file; Screenshot: a PNG to write after the frame is drawn
};

/// Reads a script: one event per line, `FRAME WHAT ARGS...`, blank lines and `#` comments skipped
/// (the grammar is in docs/viewer.md). A drag becomes a press, one move per frame and a release.
/// Events are returned in frame order, those of one frame in the file's order. Throws Error naming
/// `path:line` for a bad line, and for a frame after `lastFrame` (0: no limit) or a position
/// outside width x height.
std::vector<InputEvent> readInputScript(const std::filesystem::path& path, int lastFrame, int width,
                                        int height);

/// The GLFW key code of a key name in a script ("space", "right", "escape", "a" ... "z", "0" ...
/// "9", "[", "]"); 0 when unknown.
int keyFromName(const std::string& name);

} // namespace glcollide::viewer
