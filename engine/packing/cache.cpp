#include "engine/packing/cache.hpp"

#include <unistd.h>

#include <atomic>
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <system_error>

namespace rockcal {
namespace {

namespace fs = std::filesystem;

constexpr char kMagic[8] = {'R', 'C', 'P', 'A', 'C', 'K', '1', '\n'};
// Written in native byte order; a file from a machine of the other order fails this check.
constexpr std::uint32_t kByteOrder = 0x01020304;

std::uint64_t fnv1a(const char* data, std::size_t n) {
  std::uint64_t h = 1469598103934665603ull;
  for (std::size_t k = 0; k < n; ++k) {
    h ^= static_cast<unsigned char>(data[k]);
    h *= 1099511628211ull;
  }
  return h;
}

// Hex-float ("%a") spelling, so the key distinguishes every distinct double exactly.
std::string exact(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%a", x);
  return buf;
}

std::string key_of(const char* kind, double dim1_m, double dim2_m, const RandomPackingParams& p) {
  return "random_dense v" + std::to_string(kRandomDenseVersion) + " " + kind + " " + exact(dim1_m) +
         " " + exact(dim2_m) + " r=" + exact(p.mean_radius_m) + " ratio=" + exact(p.radius_ratio) +
         " seed=" + std::to_string(p.seed);
}
std::string key_of(const Cylinder& s, const RandomPackingParams& p) {
  return key_of("cylinder", s.diameter_m, s.height_m, p);
}
std::string key_of(const Disc& s, const RandomPackingParams& p) {
  // The flats are where the packing's walls stood (random_dense.hpp): part of its identity.
  return key_of("disc", s.diameter_m, s.thickness_m, p) + " flat=" + exact(s.flat_z_m);
}

fs::path file_for(const std::string& key, const fs::path& dir) {
  char name[40];
  std::snprintf(name, sizeof name, "rd-%016" PRIx64 ".bin", fnv1a(key.data(), key.size()));
  return dir / name;
}

template <class T>
void put(std::string& out, const T& v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof v);
}

template <class T>
bool get(const std::string& in, std::size_t& at, T& v) {
  if (in.size() - at < sizeof v) return false;
  std::memcpy(&v, in.data() + at, sizeof v);
  at += sizeof v;
  return true;
}

std::string encode(const std::string& key, const std::vector<Sphere>& spheres) {
  std::string out(kMagic, sizeof kMagic);
  put(out, kByteOrder);
  put(out, static_cast<std::uint32_t>(key.size()));
  out += key;
  put(out, static_cast<std::uint64_t>(spheres.size()));
  for (const Sphere& s : spheres) {
    put(out, s.centre.x());
    put(out, s.centre.y());
    put(out, s.centre.z());
    put(out, s.radius);
  }
  put(out, fnv1a(out.data(), out.size()));
  return out;
}

// False for anything but a complete, intact file written for exactly this key.
bool decode(const std::string& in, const std::string& key, std::vector<Sphere>& spheres) {
  std::size_t at = 0;
  std::uint32_t order = 0, key_size = 0;
  std::uint64_t count = 0, checksum = 0;
  if (in.size() < sizeof kMagic + sizeof checksum ||
      std::memcmp(in.data(), kMagic, sizeof kMagic) != 0)
    return false;
  at = sizeof kMagic;
  if (!get(in, at, order) || order != kByteOrder || !get(in, at, key_size)) return false;
  if (in.size() - at < key_size || in.compare(at, key_size, key) != 0 || key_size != key.size())
    return false;
  at += key_size;
  if (!get(in, at, count)) return false;
  constexpr std::size_t kRecord = 4 * sizeof(double);
  if ((in.size() - at) / kRecord < count || in.size() - at != count * kRecord + sizeof checksum)
    return false;
  const std::size_t payload = in.size() - sizeof checksum;
  std::size_t tail = payload;
  if (!get(in, tail, checksum) || checksum != fnv1a(in.data(), payload)) return false;
  spheres.resize(count);
  for (Sphere& s : spheres) {
    double x = 0, y = 0, z = 0;
    get(in, at, x);
    get(in, at, y);
    get(in, at, z);
    get(in, at, s.radius);
    s.centre = Vec3(x, y, z);
  }
  return true;
}

bool read_file(const fs::path& path, std::string& out) {
  std::ifstream f(path, std::ios::binary);
  if (!f) return false;
  out.assign(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
  return !f.bad();
}

// Temporary name unique per process and call, then rename: readers see the old file or the new
// one, never a partial write, and two workers storing the same packing both succeed.
void write_atomically(const fs::path& path, const std::string& bytes) {
  static std::atomic<unsigned> counter{0};
  std::error_code ec;
  fs::create_directories(path.parent_path(), ec);
  fs::path tmp = path;
  tmp += ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f) return;
    f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    f.close();
    if (!f) {
      fs::remove(tmp, ec);
      return;
    }
  }
  fs::rename(tmp, path, ec);
  if (ec) fs::remove(tmp, ec);
}

std::vector<Sphere> cached(const std::string& key, const fs::path& dir,
                           const std::function<std::vector<Sphere>()>& generate) {
  const fs::path path = file_for(key, dir);
  std::string bytes;
  std::vector<Sphere> spheres;
  if (read_file(path, bytes) && decode(bytes, key, spheres)) return spheres;
  spheres = generate();
  write_atomically(path, encode(key, spheres));
  return spheres;
}

}  // namespace

fs::path default_packing_cache_dir() {
  if (const char* d = std::getenv("ROCKCAL_PACKING_CACHE"); d && *d) return d;
  if (const char* d = std::getenv("XDG_CACHE_HOME"); d && *d)
    return fs::path(d) / "rockcal" / "packings";
  const char* home = std::getenv("HOME");
  return fs::path(home && *home ? home : ".") / ".cache" / "rockcal" / "packings";
}

fs::path packing_cache_file(const Cylinder& s, const RandomPackingParams& p, const fs::path& dir) {
  return file_for(key_of(s, p), dir);
}
fs::path packing_cache_file(const Disc& s, const RandomPackingParams& p, const fs::path& dir) {
  return file_for(key_of(s, p), dir);
}

std::vector<Sphere> cached_random_dense(const Cylinder& s, const RandomPackingParams& p,
                                        const fs::path& dir) {
  return cached(key_of(s, p), dir, [&] { return random_dense_spheres(s, p); });
}
std::vector<Sphere> cached_random_dense(const Disc& s, const RandomPackingParams& p,
                                        const fs::path& dir) {
  return cached(key_of(s, p), dir, [&] { return random_dense_spheres(s, p); });
}

}  // namespace rockcal
