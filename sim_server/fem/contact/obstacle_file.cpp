#include "fem/contact/obstacle_file.hpp"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cctype>
#include <filesystem>
#include <stdexcept>

namespace tongue::fem {

TriangleSurface read_triangle_surface(const std::string& path) {
  const auto fail = [&](const std::string& why) {
    return std::runtime_error("obstacle file " + path + ": " + why);
  };
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension != ".obj" && extension != ".stl")
    throw fail("expected a Wavefront .obj or an .stl file");
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) throw fail("no such file");

  Assimp::Importer importer;
  // Only the triangles matter: drop normals, colours and textures before they are read.
  importer.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS,
                              aiComponent_NORMALS | aiComponent_TANGENTS_AND_BITANGENTS |
                                  aiComponent_COLORS | aiComponent_TEXCOORDS |
                                  aiComponent_MATERIALS);
  const aiScene* scene = importer.ReadFile(
      path, aiProcess_RemoveComponent | aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                aiProcess_PreTransformVertices | aiProcess_ValidateDataStructure);
  if (scene == nullptr)
    throw fail(std::string("not readable as a mesh: ") + importer.GetErrorString());

  TriangleSurface surface;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh& mesh = *scene->mMeshes[m];
    const int offset = static_cast<int>(surface.vertices.size());
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D& p = mesh.mVertices[v];
      surface.vertices.emplace_back(p.x, p.y, p.z);
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) {
        throw fail("mesh " + std::to_string(m) + " has a point or line primitive (face " +
                   std::to_string(f) + " with " + std::to_string(face.mNumIndices) +
                   " vertices); only triangles and polygons describe a surface");
      }
      surface.triangles.push_back({offset + static_cast<int>(face.mIndices[0]),
                                   offset + static_cast<int>(face.mIndices[1]),
                                   offset + static_cast<int>(face.mIndices[2])});
    }
  }
  if (surface.triangles.empty()) throw fail("no triangles");
  return surface;
}

}  // namespace tongue::fem
