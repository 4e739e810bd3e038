#pragma once
// `glcollide render --video`: frames piped to the ffmpeg program (H.264 in MP4), nothing written
// but the video. GL-free; POSIX (pipe, fork, exec).

#include <cstdint>
#include <string>
#include <vector>

namespace glcollide::app {

/// The path of `program` on PATH, or empty when there is none.
std::string findOnPath(const std::string& program);

class VideoPipe {
  public:
    /// Starts `ffmpeg` writing `path` (H.264, yuv420p, padded to even sizes) from raw RGBA frames of
    /// width x height at `framesPerSecond`. Throws Error when ffmpeg is not on PATH or cannot start.
    VideoPipe(const std::string& path, int width, int height, double framesPerSecond);
    /// If finish() was not called (an error stopped the frames): closes the pipe, reaps ffmpeg and
    /// removes the partial video (no throw).
    ~VideoPipe();
    VideoPipe(const VideoPipe&) = delete;
    VideoPipe& operator=(const VideoPipe&) = delete;

    /// One frame, rows top to bottom, 4 bytes per pixel. Throws Error when ffmpeg stopped reading.
    void write(const std::vector<std::uint8_t>& rgba);
    /// Closes the pipe and waits for ffmpeg; when it failed, removes the video and throws Error with
    /// its exit status.
    void finish();

  private:
    std::string m_path;
    std::size_t m_frameBytes = 0;
    int m_fd = -1;
    int m_pid = -1;
};

} // namespace glcollide::app
