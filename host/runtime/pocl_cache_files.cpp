#include "host/runtime/pocl_cache_files.h"

#include <elf.h>
#include <fmt/format.h>

#include <algorithm>
#include <cstring>

namespace depthprec {

namespace fs = std::filesystem;

namespace {

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

bool starts_with(const std::string& s, const std::string& head) {
  return s.compare(0, head.size(), head) == 0;
}

// A name PoCL gives a file while it writes it (tempfile_XXXXXX..., tempdir_XXXXXX, <name>_XXXXXX
// .temp) or a directory of a cache-less build (_UNCACHED_XXXXXX): not a file it will load by name.
bool is_temporary(const std::string& name) {
  return starts_with(name, "tempfile_") || starts_with(name, "tempdir_") ||
         starts_with(name, "_UNCACHED") || ends_with(name, ".temp");
}

template <class T>
bool read_at(const std::string& bytes, std::uint64_t offset, T& out) {
  if (offset > bytes.size() || bytes.size() - offset < sizeof(T)) return false;
  std::memcpy(&out, bytes.data() + offset, sizeof(T));
  return true;
}

// Whether [offset, offset + count * size) lies within the file.
bool fits(std::uint64_t offset, std::uint64_t count, std::uint64_t size, std::uint64_t total) {
  if (size != 0 && count > total / size) return false;
  return offset <= total && count * size <= total - offset;
}

// A 64-bit ELF shared object (what PoCL links on x86-64 and AArch64 hosts) whose every part
// dlopen() reads or maps lies within the file.
std::string elf_problem(const std::string& bytes) {
  Elf64_Ehdr h;
  if (!read_at(bytes, 0, h) || std::memcmp(h.e_ident, ELFMAG, SELFMAG) != 0)
    return fmt::format("not an ELF file ({} bytes, ELF header missing)", bytes.size());
  if (h.e_ident[EI_CLASS] != ELFCLASS64) return "not a 64-bit ELF file";
  const std::uint64_t total = bytes.size();
  if (!fits(h.e_phoff, h.e_phnum, h.e_phentsize, total) ||
      !fits(h.e_shoff, h.e_shnum, h.e_shentsize, total) || h.e_phentsize < sizeof(Elf64_Phdr))
    return fmt::format("cut short: its headers reach past its {} bytes", total);
  for (unsigned i = 0; i < h.e_phnum; ++i) {
    Elf64_Phdr p;
    read_at(bytes, h.e_phoff + std::uint64_t{i} * h.e_phentsize, p);
    if (!fits(p.p_offset, 1, p.p_filesz, total))
      return fmt::format("cut short: segment {} ends at byte {}, past its {} bytes", i,
                         p.p_offset + p.p_filesz, total);
  }
  return "";
}

// LLVM bitcode (raw, as PoCL writes program.bc): the magic 'BC' 0xC0DE, then top-level blocks
// only, each an ENTER_SUBBLOCK (abbreviation id 1 in 2 bits, block id in VBR-8, abbreviation
// width in VBR-4, alignment to 32 bits, the block's length in 32-bit words), ending exactly at the
// end of the file.
std::string bitcode_problem(const std::string& bytes) {
  if (bytes.size() < 8 || std::memcmp(bytes.data(), "BC\xC0\xDE", 4) != 0)
    return fmt::format("not LLVM bitcode ({} bytes, magic missing)", bytes.size());
  if (bytes.size() % 4 != 0)
    return fmt::format("cut short: {} bytes is not a whole number of 32-bit words", bytes.size());
  const std::uint64_t total_bits = std::uint64_t{bytes.size()} * 8;
  std::uint64_t pos = 32;
  bool overrun = false;
  const auto bits = [&](unsigned n) {
    std::uint64_t v = 0;
    for (unsigned i = 0; i < n; ++i, ++pos) {
      if (pos >= total_bits) {
        overrun = true;
        return v;
      }
      const unsigned char byte = static_cast<unsigned char>(bytes[pos / 8]);
      v |= std::uint64_t{(byte >> (pos % 8)) & 1u} << i;
    }
    return v;
  };
  const auto vbr = [&](unsigned n) {
    std::uint64_t v = 0;
    for (unsigned shift = 0; shift < 64 && !overrun; shift += n - 1) {
      const std::uint64_t chunk = bits(n);
      v |= (chunk & ((1u << (n - 1)) - 1)) << shift;
      if (!(chunk >> (n - 1))) break;
    }
    return v;
  };
  int blocks = 0;
  while (pos < total_bits) {
    if (bits(2) != 1 || overrun)
      return fmt::format("damaged: top-level entry {} at byte {} is not a block", blocks + 1,
                         pos / 8);
    vbr(8);
    vbr(4);
    pos = (pos + 31) / 32 * 32;
    const std::uint64_t words = bits(32);
    if (overrun || words > (total_bits - pos) / 32)
      return fmt::format("cut short: block {} runs past its {} bytes", blocks + 1, bytes.size());
    pos += words * 32;
    ++blocks;
  }
  return blocks == 0 ? "cut short: no block after the magic" : "";
}

}  // namespace

std::vector<std::string> pocl_code_files(const fs::path& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return out;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::end(it);
       it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (it->is_directory(ec)) {
      if (is_temporary(name)) it.disable_recursion_pending();
      continue;
    }
    if (is_temporary(name) || !(ends_with(name, ".so") || ends_with(name, ".bc"))) continue;
    if (!it->is_regular_file(ec)) continue;
    // lexical: the iterator's paths start with dir (fs::relative would resolve every component
    // of every path through readlink, most of the check's cost)
    out.push_back(it->path().lexically_relative(dir).generic_string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::string pocl_file_structure_problem(const std::string& relative_path,
                                        const std::string& bytes) {
  if (ends_with(relative_path, ".so")) return elf_problem(bytes);
  if (ends_with(relative_path, ".bc")) return bitcode_problem(bytes);
  return "";
}

bool is_pocl_cache_entry(const std::string& name) {
  const bool program_dir =
      name.size() == 2 && std::all_of(name.begin(), name.end(), [](char c) {
        return c >= 'A' && c <= 'P';  // PoCL spells a hash's nibbles as 'A' + value
      });
  return program_dir || is_temporary(name) || starts_with(name, "depthprec-manifest") ||
         name == "depthprec.lock" || name == "depthprec.users";
}

std::uint64_t file_checksum(const std::string& bytes) {
  // FNV-1a's constants over 8-byte words with a shift to mix the high bits down: a fixed
  // function (manifests outlive a build, unlike std::hash's promise), about 1 ns per word.
  std::uint64_t h = 0xcbf29ce484222325ull;
  const std::uint64_t prime = 0x100000001b3ull;
  size_t i = 0;
  for (; i + 8 <= bytes.size(); i += 8) {
    std::uint64_t w;
    std::memcpy(&w, bytes.data() + i, 8);
    h = (h ^ w) * prime;
    h ^= h >> 29;
  }
  for (; i < bytes.size(); ++i) h = (h ^ static_cast<unsigned char>(bytes[i])) * prime;
  return h ^ bytes.size();
}

}  // namespace depthprec
