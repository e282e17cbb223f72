#include "collision/object.h"

#include "collision/thickness.h"

namespace polysim::collision {

int ObjectDatabase::add(std::string name, std::shared_ptr<const PolygonMesh> mesh, const Eigen::Isometry3d& X_WO,
                        bool isStatic, int halvings) {
  ObjNode node;
  node.name = std::move(name);
  node.grid = std::make_shared<VoxelGrid>(*mesh, halvings < 0 ? VoxelGrid::chooseHalvings(*mesh) : halvings, tolerance);
  node.thickness = minimumThickness(*mesh, *node.grid);
  node.mesh = std::move(mesh);
  node.X_WO = X_WO;
  node.isStatic = isStatic;
  node.id = static_cast<int>(objects.size());
  objects.push_back(std::move(node));
  return static_cast<int>(objects.size()) - 1;
}

void ObjectDatabase::setTime(double t) {
  for (ObjNode& o : objects)
    if (o.ctrans) o.ctrans(t, o.info, o.X_WO);
}

}  // namespace polysim::collision
