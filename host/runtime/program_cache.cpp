#include "host/runtime/program_cache.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <sstream>

#include "host/base/errors.h"

namespace depthprec {

namespace fs = std::filesystem;

namespace {

constexpr const char* kMagic = "depthprec-program-binary 1\n";

size_t checksum(const std::vector<unsigned char>& b) {
  return std::hash<std::string>{}(std::string(b.begin(), b.end()));
}

std::optional<std::vector<unsigned char>> read_entry(const fs::path& path, const std::string& key) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::string magic(std::char_traits<char>::length(kMagic), '\0');
  in.read(magic.data(), static_cast<std::streamsize>(magic.size()));
  size_t key_size = 0, size = 0, sum = 0;
  if (!in || magic != kMagic || !(in >> key_size >> size >> sum) || in.get() != '\n')
    return std::nullopt;
  if (key_size != key.size() || size > (size_t{1} << 31)) return std::nullopt;
  std::string stored_key(key_size, '\0');
  in.read(stored_key.data(), static_cast<std::streamsize>(key_size));
  if (!in || stored_key != key) return std::nullopt;  // another program with the same name hash
  std::vector<unsigned char> binary(size);
  in.read(reinterpret_cast<char*>(binary.data()), static_cast<std::streamsize>(size));
  if (!in || in.peek() != std::char_traits<char>::eof() || checksum(binary) != sum)
    return std::nullopt;  // truncated, extended or damaged
  return binary;
}

}  // namespace

ProgramBinaryCache::ProgramBinaryCache(std::string writable, std::vector<std::string> prebuilt)
    : writable_(std::move(writable)), prebuilt_(std::move(prebuilt)) {}

ProgramBinaryCache ProgramBinaryCache::from_environment() {
  const char* chosen = std::getenv("DEPTHPREC_KERNEL_CACHE");
  if (chosen && std::string(chosen) == "off") return ProgramBinaryCache("", {});
  const std::string writable = chosen ? chosen : "";
  std::vector<std::string> prebuilt;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    prebuilt.push_back((exe.parent_path() / "kernel-cache").string());
    prebuilt.push_back(
        (exe.parent_path().parent_path() / "share" / "depthprec" / "kernels").string());
  }
  return ProgramBinaryCache(writable, prebuilt);
}

std::string ProgramBinaryCache::file_name(const std::string& key) const {
  return fmt::format("{:016x}.bin", std::hash<std::string>{}(key));
}

std::optional<std::vector<unsigned char>> ProgramBinaryCache::load(const std::string& key) const {
  std::vector<std::string> dirs;
  if (!writable_.empty()) dirs.push_back(writable_);
  dirs.insert(dirs.end(), prebuilt_.begin(), prebuilt_.end());
  for (const auto& dir : dirs)
    if (auto b = read_entry(fs::path(dir) / file_name(key), key)) return b;
  return std::nullopt;
}

void ProgramBinaryCache::store(const std::string& key,
                               const std::vector<unsigned char>& binary) const {
  if (writable_.empty() || binary.empty()) return;
  std::error_code ec;
  fs::create_directories(writable_, ec);
  const fs::path path = fs::path(writable_) / file_name(key);
  const fs::path tmp = path.string() + fmt::format(".{}.tmp", ::getpid());
  {
    std::ofstream out(tmp, std::ios::binary);
    out << kMagic << key.size() << ' ' << binary.size() << ' ' << checksum(binary) << '\n' << key;
    out.write(reinterpret_cast<const char*>(binary.data()),
              static_cast<std::streamsize>(binary.size()));
    if (!out) {
      fs::remove(tmp, ec);
      return;
    }
  }
  fs::rename(tmp, path, ec);
  if (ec) fs::remove(tmp, ec);
}

void ProgramBinaryCache::forget(const std::string& key) const {
  if (writable_.empty()) return;
  std::error_code ec;
  fs::remove(fs::path(writable_) / file_name(key), ec);
}

std::uintmax_t ProgramBinaryCache::clear() const {
  std::uintmax_t bytes = 0;
  std::error_code ec;
  if (writable_.empty() || !fs::is_directory(writable_, ec)) return 0;
  std::vector<fs::path> doomed;
  for (const auto& e : fs::directory_iterator(writable_, ec)) {
    const std::string name = e.path().filename().string();
    // file_name()'s "<16 hex digits>.bin", or store()'s "<16 hex digits>.bin.<pid>.tmp"
    const bool hex = name.size() >= 20 && std::all_of(name.begin(), name.begin() + 16, [](char c) {
                       return std::isxdigit(static_cast<unsigned char>(c));
                     });
    const bool entry = hex && name.size() == 20 && name.compare(16, 4, ".bin") == 0;
    const bool partial = hex && name.compare(16, 5, ".bin.") == 0 && name.size() > 25 &&
                         name.compare(name.size() - 4, 4, ".tmp") == 0;
    if ((entry || partial) && e.is_regular_file(ec)) doomed.push_back(e.path());
  }
  for (const fs::path& p : doomed) {
    bytes += fs::file_size(p, ec);
    fs::remove(p, ec);
    if (ec) throw RuntimeError(fmt::format("cannot remove {}: {}", p.string(), ec.message()));
  }
  return bytes;
}

}  // namespace depthprec
