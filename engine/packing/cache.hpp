// A file cache of random dense packings, so that a parameter sweep generates each packing once.
// Files are keyed by a hash of everything that determines the packing (shape kind and dimensions,
// radius parameters, seed and generator version), written atomically (temporary file + rename)
// so concurrent workers never read half a file, and checked on reading (size, key, checksum):
// a corrupt or truncated file is regenerated and replaced.
#pragma once

#include <filesystem>
#include <vector>

#include "engine/packing/random_dense.hpp"

namespace rockcal {

// $ROCKCAL_PACKING_CACHE, else $XDG_CACHE_HOME/rockcal/packings, else ~/.cache/rockcal/packings.
std::filesystem::path default_packing_cache_dir();

// Where the packing for these parameters is (or would be) stored in cache_dir.
std::filesystem::path packing_cache_file(const Cylinder& shape, const RandomPackingParams& p,
                                         const std::filesystem::path& cache_dir);
std::filesystem::path packing_cache_file(const Disc& shape, const RandomPackingParams& p,
                                         const std::filesystem::path& cache_dir);

// The cached packing if a valid one exists, else random_dense_spheres() stored for next time. A
// cache directory that cannot be written only costs the regeneration next time.
std::vector<Sphere> cached_random_dense(const Cylinder& shape, const RandomPackingParams& p,
                                        const std::filesystem::path& cache_dir);
std::vector<Sphere> cached_random_dense(const Disc& shape, const RandomPackingParams& p,
                                        const std::filesystem::path& cache_dir);

}  // namespace rockcal
