#pragma once
// Welding and validation sharing their scratch arrays (triangle_mesh.cpp; used by
// mesh_mass.cpp). In a fresh process every 4 KB page of new memory costs a page fault the first
// time it is touched, so the arrays welding is done with are handed to validation, with their
// pages already present, instead of being freed and allocated again.

#include <cstdint>
#include <span>
#include <vector>

#include "chasles/mass/triangle_mesh.h"

namespace chasles::internal {

/// Scratch arrays: welding's hash table, chains and cell keys, then validation's union-find
/// parents, bucket offsets and edge buckets.
struct MeshWorkspace {
  std::vector<std::uint32_t> table;
  std::vector<std::uint32_t> next;
  std::vector<std::uint64_t> keys;
};

/// BuildTriangleMesh, BuildTriangleSoup and ValidateSolid (chasles/mass/triangle_mesh.h) with
/// the scratch arrays in `workspace`.
TriangleMesh BuildTriangleMesh(std::span<const double> xyz, std::span<const std::uint32_t> indices,
                               double scale, double tolerance, MeshRepairReport* report,
                               MeshWorkspace& workspace);
TriangleMesh BuildTriangleSoup(std::span<const float> xyz, double scale, double tolerance,
                               MeshRepairReport* report, MeshWorkspace& workspace);
TriangleMesh BuildTriangleSoup(const FloatSoupRecords& records, double scale, double tolerance,
                               MeshRepairReport* report, MeshWorkspace& workspace);
void ValidateSolid(TriangleMesh& mesh, MeshRepairReport* report, MeshWorkspace& workspace);

}  // namespace chasles::internal
