#include "lang2manip/model/triangle_mesh.hpp"

namespace lang2manip {

AlignedBox3 TriangleMesh::bounds() const {
  AlignedBox3 box;  // Eigen's default box is empty.
  for (const Vector3& vertex : vertices) box.extend(vertex);
  return box;
}

}  // namespace lang2manip
