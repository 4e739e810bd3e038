#include "viewer/input_script.hpp"

#include <glcollide/error.hpp>

#include <GLFW/glfw3.h>

#include <algorithm>
#include <fstream>
#include <sstream>

namespace glcollide::viewer {
namespace {

/// Reading one line: every problem names the file and line.
class LineReader {
  public:
    LineReader(std::string where, const std::string& text) : m_where(std::move(where)), m_in(text) {}
    [[noreturn]] void fail(const std::string& message) const { throw Error(m_where + ": " + message); }
    bool word(std::string& out) { return static_cast<bool>(m_in >> out); }
    std::string need(const char* what) {
        std::string w;
        if (!word(w)) fail(std::string("expected ") + what);
        return w;
    }
    double number(const char* what) {
        const std::string w = need(what);
        std::size_t used = 0;
        double value = 0.0;
        try {
            value = std::stod(w, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used != w.size()) fail(std::string("expected ") + what + " (a number), got '" + w + "'");
        return value;
    }
    int integer(const char* what, int lowest) {
        const std::string w = need(what);
        std::size_t used = 0;
        long value = 0;
        try {
            value = std::stol(w, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used != w.size() || value < lowest || value > 100000000)
            fail(std::string("expected ") + what + " (an integer >= " + std::to_string(lowest) + "), got '" +
                 w + "'");
        return static_cast<int>(value);
    }
    std::string rest() {
        std::string r;
        std::getline(m_in, r);
        const auto first = r.find_first_not_of(" \t");
        if (first == std::string::npos) return {};
        r = r.substr(first);
        while (!r.empty() && (r.back() == ' ' || r.back() == '\t' || r.back() == '\r')) r.pop_back();
        return r;
    }
    /// Optional trailing modifiers: ctrl, shift.
    int modifiers() {
        int mods = 0;
        std::string w;
        while (word(w)) {
            if (w == "ctrl")
                mods |= GLFW_MOD_CONTROL;
            else if (w == "shift")
                mods |= GLFW_MOD_SHIFT;
            else
                fail("unexpected '" + w + "' (modifiers: ctrl, shift)");
        }
        return mods;
    }

  private:
    std::string m_where;
    std::istringstream m_in;
};

int buttonFromName(const std::string& name) {
    if (name == "left") return GLFW_MOUSE_BUTTON_LEFT;
    if (name == "right") return GLFW_MOUSE_BUTTON_RIGHT;
    if (name == "middle") return GLFW_MOUSE_BUTTON_MIDDLE;
    return -1;
}

} // namespace

int keyFromName(const std::string& name) {
    if (name == "space") return GLFW_KEY_SPACE;
    if (name == "right") return GLFW_KEY_RIGHT;
    if (name == "left") return GLFW_KEY_LEFT;
    if (name == "escape") return GLFW_KEY_ESCAPE;
    if (name == "[") return GLFW_KEY_LEFT_BRACKET;
    if (name == "]") return GLFW_KEY_RIGHT_BRACKET;
    if (name == ".") return GLFW_KEY_PERIOD;
    if (name == "-") return GLFW_KEY_MINUS;
    if (name == "=") return GLFW_KEY_EQUAL;
    if (name.size() == 1 && name[0] >= 'a' && name[0] <= 'z') return GLFW_KEY_A + (name[0] - 'a');
    if (name.size() == 1 && name[0] >= 'A' && name[0] <= 'Z') return GLFW_KEY_A + (name[0] - 'A');
    if (name.size() == 1 && name[0] >= '0' && name[0] <= '9') return GLFW_KEY_0 + (name[0] - '0');
    return 0;
}

std::vector<InputEvent> readInputScript(const std::filesystem::path& path, int lastFrame, int width,
                                        int height) {
    std::ifstream file(path);
    if (!file) throw Error(path.string() + ": cannot read the input script");
    std::vector<InputEvent> events;
    std::string line;
    int lineNumber = 0;
    while (std::getline(file, line)) {
        ++lineNumber;
        const auto first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos || line[first] == '#') continue;
        LineReader in(path.string() + ":" + std::to_string(lineNumber), line);
        InputEvent e;
        e.frame = in.integer("a frame number", 1);
        if (lastFrame > 0 && e.frame > lastFrame)
            in.fail("frame " + std::to_string(e.frame) + " is after the last frame (--frames " +
                    std::to_string(lastFrame) + ")");
        auto position = [&](double& x, double& y) {
            x = in.number("x in pixels");
            y = in.number("y in pixels");
            if (!(x >= 0.0 && x < width && y >= 0.0 && y < height))
                in.fail("position (" + std::to_string(x) + ", " + std::to_string(y) + ") is outside the " +
                        std::to_string(width) + "x" + std::to_string(height) + " window");
        };
        const std::string what = in.need("an event: key, drag, scroll, open or screenshot");
        if (what == "key") {
            const std::string name = in.need("a key name");
            e.key = keyFromName(name);
            if (e.key == 0) in.fail("unknown key '" + name + "' (docs/viewer.md lists the names)");
            e.mods = in.modifiers();
            events.push_back(e);
        } else if (what == "drag") {
            const std::string name = in.need("a mouse button: left, right or middle");
            e.button = buttonFromName(name);
            if (e.button < 0) in.fail("unknown mouse button '" + name + "' (left, right or middle)");
            double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
            position(x0, y0);
            position(x1, y1);
            const int frames = in.integer("the drag's length in frames", 1);
            e.mods = in.modifiers();
            if (lastFrame > 0 && e.frame + frames > lastFrame)
                in.fail("the drag ends at frame " + std::to_string(e.frame + frames) +
                        ", after the last frame (--frames " + std::to_string(lastFrame) + ")");
            // Press where it starts, one move per frame along the line, release where it ends.
            InputEvent press = e;
            press.kind = InputEvent::Kind::MouseDown;
            press.x = x0;
            press.y = y0;
            events.push_back(press);
            for (int k = 1; k <= frames; ++k) {
                InputEvent move = e;
                move.kind = InputEvent::Kind::MouseMove;
                move.frame = e.frame + k;
                const double t = static_cast<double>(k) / frames;
                move.x = x0 + t * (x1 - x0);
                move.y = y0 + t * (y1 - y0);
                events.push_back(move);
            }
            InputEvent release = events.back();
            release.kind = InputEvent::Kind::MouseUp;
            events.push_back(release);
        } else if (what == "scroll") {
            e.kind = InputEvent::Kind::Scroll;
            e.scroll = in.number("wheel steps");
            e.x = width / 2.0;
            e.y = height / 2.0;
            if (!in.rest().empty()) in.fail("scroll takes one number (wheel steps)");
            events.push_back(e);
        } else if (what == "open" || what == "screenshot") {
            e.kind = what == "open" ? InputEvent::Kind::Open : InputEvent::Kind::Screenshot;
            e.path = in.rest();
            if (e.path.empty()) in.fail(std::string("expected a file path after '") + what + "'");
            events.push_back(e);
        } else {
            in.fail("unknown event '" + what + "' (key, drag, scroll, open or screenshot)");
        }
    }
    std::stable_sort(events.begin(), events.end(),
                     [](const InputEvent& a, const InputEvent& b) { return a.frame < b.frame; });
    return events;
}

} // namespace glcollide::viewer
