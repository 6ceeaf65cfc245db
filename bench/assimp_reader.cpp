#include "assimp_reader.h"

#include <cstdint>

#include <assimp/mesh.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fmt/format.h>
#include <assimp/Importer.hpp>

#include "chasles/error.h"

namespace chasles::bench {

MeshFileData ReadWithAssimp(const std::string& path) {
  Assimp::Importer importer;
  // Only faces are wanted: drop lines and points instead of having them split into meshes.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                              aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* scene =
      importer.ReadFile(path, aiProcess_ValidateDataStructure | aiProcess_Triangulate |
                                  aiProcess_PreTransformVertices | aiProcess_SortByPType);
  if (scene == nullptr) {
    const std::string why = importer.GetErrorString();
    // Point clouds and line sets are read, but their primitives are dropped above.
    if (why.find("No output meshes") != std::string::npos) {
      throw InputError(
          fmt::format("mesh file '{}': empty mesh (no triangles found; {})", path, why));
    }
    throw InputError(
        fmt::format("mesh file '{}': unreadable or garbled ({})", path, importer.GetErrorString()));
  }
  MeshFileData data;
  data.format = "assimp";
  data.single_precision = true;  // assimp's ai_real is a float
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    if ((mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) == 0) continue;
    const std::size_t base = data.vertex_count();
    if (base + mesh->mNumVertices > std::size_t{UINT32_MAX}) {
      throw InputError(fmt::format("mesh file '{}': more than 2^32 vertices", path));
    }
    data.xyz.reserve(data.xyz.size() + 3 * std::size_t{mesh->mNumVertices});
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& p = mesh->mVertices[v];
      data.xyz.push_back(static_cast<double>(p.x));
      data.xyz.push_back(static_cast<double>(p.y));
      data.xyz.push_back(static_cast<double>(p.z));
    }
    for (unsigned t = 0; t < mesh->mNumFaces; ++t) {
      const aiFace& face = mesh->mFaces[t];
      if (face.mNumIndices != 3) continue;
      for (int k = 0; k < 3; ++k) {
        data.indices.push_back(static_cast<std::uint32_t>(base + face.mIndices[k]));
      }
    }
  }
  if (data.indices.empty()) {
    throw InputError(fmt::format("mesh file '{}': empty mesh (no triangles found in the {} data)",
                                 path, data.format));
  }
  return data;
}

}  // namespace chasles::bench
