#include "app/video_pipe.hpp"

#include <glcollide/error.hpp>

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <string_view>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

namespace glcollide::app {

std::string findOnPath(const std::string& program) {
    const char* path = std::getenv("PATH");
    std::string_view rest = path ? path : "/usr/bin:/bin";
    while (true) {
        const std::size_t colon = rest.find(':');
        const std::string dir(rest.substr(0, colon));
        const std::string candidate = (dir.empty() ? "." : dir) + "/" + program;
        struct stat st {};
        if (::stat(candidate.c_str(), &st) == 0 && S_ISREG(st.st_mode) &&
            ::access(candidate.c_str(), X_OK) == 0)
            return candidate;
        if (colon == std::string_view::npos) return {};
        rest.remove_prefix(colon + 1);
    }
}

VideoPipe::VideoPipe(const std::string& path, int width, int height, double framesPerSecond)
    : m_path(path), m_frameBytes(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4) {
    const std::string ffmpeg = findOnPath("ffmpeg");
    if (ffmpeg.empty())
        throw Error(
            "--video needs the ffmpeg program, which is not on PATH (Debian: apt-get install ffmpeg)");
    std::ostringstream size, rate;
    size << width << "x" << height;
    rate.precision(17);
    rate << framesPerSecond;
    // ffmpeg reads raw RGBA from stdin; H.264 needs even sizes (the pad filter adds a row or a
    // column), yuv420p plays everywhere, +faststart puts the index first.
    const std::vector<std::string> args = {
        ffmpeg,      "-loglevel",  "error",      "-y",
        "-f",        "rawvideo",   "-pix_fmt",   "rgba",
        "-s",        size.str(),   "-framerate", rate.str(),
        "-i",        "-",          "-vf",        "pad=ceil(iw/2)*2:ceil(ih/2)*2",
        "-c:v",      "libx264",    "-pix_fmt",   "yuv420p",
        "-movflags", "+faststart", path};
    int fds[2];
    if (::pipe(fds) != 0) throw Error(std::string("--video: pipe: ") + std::strerror(errno));
    const pid_t pid = ::fork();
    if (pid < 0) {
        ::close(fds[0]);
        ::close(fds[1]);
        throw Error(std::string("--video: fork: ") + std::strerror(errno));
    }
    if (pid == 0) { // child: stdin from the pipe, then ffmpeg
        ::dup2(fds[0], STDIN_FILENO);
        ::close(fds[0]);
        ::close(fds[1]);
        std::vector<char*> argv;
        for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        ::execv(argv[0], argv.data());
        ::_exit(127);
    }
    ::close(fds[0]);
    m_fd = fds[1];
    m_pid = pid;
    std::signal(SIGPIPE, SIG_IGN); // a stopped ffmpeg makes write() fail with EPIPE, not kill us
}

void VideoPipe::write(const std::vector<std::uint8_t>& rgba) {
    if (rgba.size() != m_frameBytes) throw Error("--video: a frame of the wrong size");
    std::size_t done = 0;
    while (done < rgba.size()) {
        const ssize_t n = ::write(m_fd, rgba.data() + done, rgba.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) throw Error("--video: ffmpeg stopped reading frames for " + m_path);
        done += static_cast<std::size_t>(n);
    }
}

void VideoPipe::finish() {
    if (m_pid < 0) return;
    ::close(m_fd);
    m_fd = -1;
    int status = 0;
    while (::waitpid(m_pid, &status, 0) < 0 && errno == EINTR) {
    }
    m_pid = -1;
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        std::error_code ec;
        std::filesystem::remove(m_path, ec); // a failed video is not left behind half-written
        throw Error("--video: ffmpeg failed writing " + m_path + " (exit status " +
                    std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")");
    }
}

VideoPipe::~VideoPipe() {
    if (m_fd >= 0) ::close(m_fd);
    if (m_pid > 0) { // not finished: an error stopped the frames; the partial video goes too
        int status = 0;
        while (::waitpid(m_pid, &status, 0) < 0 && errno == EINTR) {
        }
        std::error_code ec;
        std::filesystem::remove(m_path, ec);
    }
}

} // namespace glcollide::app
