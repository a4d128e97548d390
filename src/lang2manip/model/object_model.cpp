#include "lang2manip/model/object_model.hpp"

#include <cstdio>

#include "lang2manip/core/rotation.hpp"
#include "lang2manip/core/text_parsing.hpp"
#include "lang2manip/model/xml_document.hpp"

namespace lang2manip {
namespace {

std::vector<Shape> shapesInRootFrame(const RobotModel& model,
                                     std::vector<Shape> Link::*member) {
  VectorX q = VectorX::Zero(model.variableCount());
  q = q.cwiseMax(model.lowerLimits()).cwiseMin(model.upperLimits());
  const std::vector<Pose> X_RL = model.linkPoses(q);
  std::vector<Shape> shapes;
  for (std::size_t l = 0; l < model.links().size(); ++l) {
    for (Shape shape : model.links()[l].*member) {
      shape.origin = X_RL[l] * shape.origin;
      shapes.push_back(std::move(shape));
    }
  }
  return shapes;
}

ObjectRole inferredRole(const SceneObject& object) {
  const Vector3 size = object.dimensions();
  const bool wide = size.x() >= 0.3 && size.y() >= 0.3;
  return wide && size.z() <= std::max(size.x(), size.y()) ? ObjectRole::kSupport : ObjectRole::kNone;
}

void applyMetadata(SceneObject& object, const std::filesystem::path& urdf, double scale) {
  const XmlDocument document = XmlDocument::loadFile(urdf, "URDF file");
  const pugi::xml_node metadata = document.root().child("lang2manip_object");
  if (!metadata) {
    object.role = inferredRole(object);
    object.semantics = SemanticsSource::kInferred;
    return;
  }
  if (const pugi::xml_attribute kind = metadata.attribute("kind")) object.kind = kind.value();
  if (const pugi::xml_attribute movable = metadata.attribute("movable")) {
    object.movable = parseFlag(movable.value(), "<lang2manip_object> attribute movable",
                               document.where(metadata));
  }
  if (const pugi::xml_attribute role = metadata.attribute("role")) {
    try {
      object.role = objectRoleFromName(role.value());
    } catch (const InputError& error) {
      throw InputError(document.where(metadata), error.what());
    }
  }
  if (const pugi::xml_node cavity = metadata.child("cavity")) {
    const SourceLocation where = document.where(cavity);
    object.cavity = AlignedBox3(scale * parseVector3(document.requiredAttribute(cavity, "min"), "<cavity> min", where),
                                scale * parseVector3(document.requiredAttribute(cavity, "max"), "<cavity> max", where));
  }
}


std::string triple(const Vector3& v) {
  return exactNumber(v.x()) + " " + exactNumber(v.y()) + " " + exactNumber(v.z());
}

std::string geometryXml(const Geometry& geometry) {
  if (const auto* box = std::get_if<Box>(&geometry)) return "<box size=\"" + triple(box->size) + "\"/>";
  if (const auto* sphere = std::get_if<Sphere>(&geometry)) {
    return "<sphere radius=\"" + exactNumber(sphere->radius) + "\"/>";
  }
  if (const auto* cylinder = std::get_if<Cylinder>(&geometry)) {
    return "<cylinder radius=\"" + exactNumber(cylinder->radius) + "\" length=\"" +
           exactNumber(cylinder->length) + "\"/>";
  }
  const auto& mesh = std::get<MeshGeometry>(geometry);
  const std::string file = mesh.mesh ? mesh.mesh->source : mesh.reference;
  return "<mesh filename=\"" + xmlEscaped(file) + "\" scale=\"" + triple(mesh.scale) + "\"/>";
}

std::string shapeXml(const Shape& shape, const char* element) {
  std::string xml = std::string("    <") + element;
  if (!shape.name.empty()) xml += " name=\"" + xmlEscaped(shape.name) + "\"";
  xml += ">\n      <origin xyz=\"" + triple(shape.origin.translation()) + "\" rpy=\"" +
         triple(rpyFromQuaternion(Quaternion(shape.origin.linear()))) + "\"/>\n      <geometry>" +
         geometryXml(shape.geometry) + "</geometry>\n";
  if (shape.material) {
    const Vector4& c = shape.material->rgba;
    xml += "      <material name=\"" + xmlEscaped(shape.material->name) + "\"><color rgba=\"" +
           exactNumber(c[0]) + " " + exactNumber(c[1]) + " " + exactNumber(c[2]) + " " + exactNumber(c[3]) +
           "\"/></material>\n";
  }
  return xml + "    </" + element + ">\n";
}

}  // namespace

SceneObject objectFromModel(const RobotModel& model, const std::string& name,
                            const std::filesystem::path& urdf, double scale) {
  SceneObject object;
  object.name = name;
  object.kind = model.name();
  object.collisions = shapesInRootFrame(model, &Link::collisions);
  object.visuals = shapesInRootFrame(model, &Link::visuals);
  object.modelSource = urdf.string();
  object.modelScale = scale;
  applyMetadata(object, urdf, scale);
  return object;
}


std::string objectUrdfString(const SceneObject& object) {
  std::string xml = "<?xml version=\"1.0\"?>\n<robot name=\"" + xmlEscaped(object.kind) + "\">\n";
  xml += "  <lang2manip_object kind=\"" + xmlEscaped(object.kind) + "\" movable=\"" +
         (object.movable ? "true" : "false") + "\" role=\"" + objectRoleName(object.role) + "\"";
  if (object.cavity) {
    xml += ">\n    <cavity min=\"" + triple(object.cavity->min()) + "\" max=\"" +
           triple(object.cavity->max()) + "\"/>\n  </lang2manip_object>\n";
  } else {
    xml += "/>\n";
  }
  xml += "  <link name=\"" + xmlEscaped(object.name) + "\">\n";
  for (const Shape& shape : object.visuals) xml += shapeXml(shape, "visual");
  for (const Shape& shape : object.collisions) xml += shapeXml(shape, "collision");
  return xml + "  </link>\n</robot>\n";
}

}  // namespace lang2manip
