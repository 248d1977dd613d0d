#include <unexmin/sim/contacts.h>

#include <btBulletDynamicsCommon.h>

namespace unexmin {
namespace sim {

std::vector<Contact> contacts(World& world, Robot& robot) {
  const btCollisionObject* body = robot.body();
  btDispatcher* dispatcher = world.physics().getDispatcher();
  std::vector<Contact> out;
  for (int i = 0; i < dispatcher->getNumManifolds(); ++i) {
    const btPersistentManifold* m = dispatcher->getManifoldByIndexInternal(i);
    const bool first = m->getBody0() == body;
    if (!first && m->getBody1() != body)
      continue;
    for (int j = 0; j < m->getNumContacts(); ++j) {
      const btManifoldPoint& p = m->getContactPoint(j);
      if (p.getDistance() > 0.0)
        continue;
      // Bullet's normal points from body 1 to body 0: turn it to point from the obstacle into the robot.
      const btVector3 at = first ? p.getPositionWorldOnB() : p.getPositionWorldOnA();
      const btVector3 n = first ? p.m_normalWorldOnB : -p.m_normalWorldOnB;
      Contact c;
      c.position = Eigen::Vector3d(at.x(), at.y(), at.z());
      c.normal = Eigen::Vector3d(n.x(), n.y(), n.z());
      c.depth = -p.getDistance();
      c.impulse = p.getAppliedImpulse();
      out.push_back(c);
    }
  }
  return out;
}

}  // namespace sim
}  // namespace unexmin
