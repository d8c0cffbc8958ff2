#include "commands/openmesh_peer.h"

#include <meshoptimizer.h>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>
#include <chrono>
#include <cmath>
#include <vector>

namespace crowdbake::bench {
namespace {

using Mesh = OpenMesh::TriMesh_ArrayKernelT<>;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

OpenMeshRun openmesh_decimate_all(const SkinnedAsset& asset, double ratio) {
  OpenMeshRun run;
  for (const Primitive& p : asset.primitives) {
    const size_t n = p.indices.size();
    std::vector<unsigned int> remap(p.vertex_count()), welded(n);
    const size_t welded_count = meshopt_generateVertexRemap(
        remap.data(), p.indices.data(), n, p.positions.data(), p.vertex_count(), sizeof(glm::vec3));
    meshopt_remapIndexBuffer(welded.data(), p.indices.data(), n, remap.data());
    std::vector<glm::vec3> positions(welded_count);
    meshopt_remapVertexBuffer(positions.data(), p.positions.data(), p.vertex_count(),
                              sizeof(glm::vec3), remap.data());

    const auto start = std::chrono::steady_clock::now();
    Mesh mesh;
    std::vector<Mesh::VertexHandle> handles(welded_count);
    for (size_t v = 0; v < welded_count; ++v)
      handles[v] = mesh.add_vertex(Mesh::Point(positions[v].x, positions[v].y, positions[v].z));
    for (size_t i = 0; i + 2 < n; i += 3) {
      const Mesh::FaceHandle f =
          mesh.add_face(handles[welded[i]], handles[welded[i + 1]], handles[welded[i + 2]]);
      if (!f.is_valid()) ++run.refused_faces;
    }
    const size_t faces = mesh.n_faces();
    OpenMesh::Decimater::DecimaterT<Mesh> decimater(mesh);
    OpenMesh::Decimater::ModQuadricT<Mesh>::Handle quadric;
    decimater.add(quadric);
    decimater.module(quadric).unset_max_err();
    decimater.initialize();
    run.build_seconds += seconds_since(start);
    decimater.decimate_to_faces(0, static_cast<size_t>(std::lround(ratio * double(faces))));
    mesh.garbage_collection();
    run.seconds += seconds_since(start);
    run.triangles += mesh.n_faces();
  }
  return run;
}

}  // namespace crowdbake::bench
