#include "io/mesh_io.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <stdexcept>
#include <string>

#include "io/file_extension.h"
#include "io/ply_reader.h"

namespace rr {

namespace {

MeshData readWithAssimp(const std::filesystem::path& file) {
    Assimp::Importer importer;
    // Joining identical vertices restores sharing (Assimp un-indexes some formats), which
    // smooth normals need; degenerate faces are dropped.
    // Validation rejects faces indexing past their mesh's vertices, among other inconsistencies
    // a damaged file can leave.
    const aiScene* scene =
        importer.ReadFile(file.string(), aiProcess_ValidateDataStructure | aiProcess_Triangulate |
                                             aiProcess_JoinIdenticalVertices |
                                             aiProcess_FindDegenerates | aiProcess_SortByPType);
    if (!scene || !scene->mRootNode)
        throw std::runtime_error("cannot read mesh " + file.string() + ": " +
                                 importer.GetErrorString());
    MeshData data;
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
        const aiMesh* mesh = scene->mMeshes[m];
        if (!(mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
        const auto base = static_cast<uint32_t>(data.positions.size());
        for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
            const aiVector3D& p = mesh->mVertices[v];
            data.positions.emplace_back(p.x, p.y, p.z);
        }
        for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
            const aiFace& face = mesh->mFaces[f];
            if (face.mNumIndices != 3) continue;
            for (int k = 0; k < 3; ++k) {
                if (face.mIndices[k] >= mesh->mNumVertices)
                    throw std::runtime_error("mesh " + file.string() + ": face " +
                                             std::to_string(f) + " indexes a missing vertex");
                data.indices.push_back(base + face.mIndices[k]);
            }
        }
    }
    return data;
}

}  // namespace

MeshData loadMesh(const std::filesystem::path& file) {
    MeshData data = lowercaseExtension(file) == ".ply" ? readPly(file) : readWithAssimp(file);
    for (size_t v = 0; v < data.positions.size(); ++v)
        if (!isFinite(data.positions[v]))
            throw std::runtime_error("mesh " + file.string() + ": vertex " + std::to_string(v) +
                                     " is not finite");
    if (data.indices.empty())
        throw std::runtime_error("mesh " + file.string() + " has no triangles");
    return data;
}

}  // namespace rr
