#include "commands/openmesh_peer.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>
#include <chrono>
#include <cmath>
#include <vector>

#include "commands/peers.h"
#include "crowdbake/base/clock.h"

namespace crowdbake::bench {
namespace {

using Mesh = OpenMesh::TriMesh_ArrayKernelT<>;

}  // namespace

OpenMeshRun openmesh_decimate_all(const SkinnedAsset& asset, double ratio) {
  OpenMeshRun run;
  for (const Primitive& p : asset.primitives) {
    const WeldedPrimitive w = weld_positions(p);
    const std::vector<unsigned int>& welded = w.indices;

    const auto start = std::chrono::steady_clock::now();
    Mesh mesh;
    std::vector<Mesh::VertexHandle> handles(w.positions.size());
    for (size_t v = 0; v < handles.size(); ++v)
      handles[v] =
          mesh.add_vertex(Mesh::Point(w.positions[v].x, w.positions[v].y, w.positions[v].z));
    for (size_t i = 0; i + 2 < welded.size(); i += 3) {
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
