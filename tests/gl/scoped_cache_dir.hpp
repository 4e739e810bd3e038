#pragma once
// Test helpers for code that reads the environment: ScopedEnv sets a variable for a scope and
// restores it; FreshCacheDir points GLCOLLIDE_CACHE_DIR at a new empty folder for a scope (the
// program cache and the self-check markers then start cold, whatever earlier runs left).

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace glcollide::test {

class ScopedEnv {
  public:
    ScopedEnv(const char* name, const std::string& value) : m_name(name) {
        if (const char* old = std::getenv(name)) m_old = old;
        ::setenv(name, value.c_str(), 1);
    }
    ~ScopedEnv() {
        if (m_old)
            ::setenv(m_name, m_old->c_str(), 1);
        else
            ::unsetenv(m_name);
    }
    ScopedEnv(const ScopedEnv&) = delete;
    ScopedEnv& operator=(const ScopedEnv&) = delete;

  private:
    const char* m_name;
    std::optional<std::string> m_old;
};

class FreshCacheDir {
  public:
    FreshCacheDir() {
        static int counter = 0;
        m_path = std::filesystem::temp_directory_path() /
                 ("glcollide-cache-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
        std::filesystem::remove_all(m_path);
        std::filesystem::create_directories(m_path);
        m_env.emplace("GLCOLLIDE_CACHE_DIR", m_path.string());
    }
    ~FreshCacheDir() {
        m_env.reset();
        std::error_code ec;
        std::filesystem::remove_all(m_path, ec);
    }
    FreshCacheDir(const FreshCacheDir&) = delete;
    FreshCacheDir& operator=(const FreshCacheDir&) = delete;
    [[nodiscard]] const std::filesystem::path& path() const { return m_path; }
    [[nodiscard]] std::vector<std::filesystem::path> files() const {
        std::vector<std::filesystem::path> out;
        for (const auto& e : std::filesystem::directory_iterator(m_path)) out.push_back(e.path());
        return out;
    }

  private:
    std::filesystem::path m_path;
    std::optional<ScopedEnv> m_env;
};

} // namespace glcollide::test
