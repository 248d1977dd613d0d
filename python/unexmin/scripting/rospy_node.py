"""This process's rospy node. rospy runs one node per process, bound for good to the master it first
registered with; these helpers let the scripting API check that binding and, when a world is
launched again on the same master port, tell the new master about the node's remaining topics."""

import xmlrpc.client

import rosgraph
import rospy


def _reg_manager():
    """rospy's registration manager of this process's node (None before init_node)."""
    from rospy.impl.registration import RegManager, get_registration_listeners

    return next((r for r in get_registration_listeners().listeners if isinstance(r, RegManager)), None)


def node_master_uri():
    """The master URI this process's rospy node registered with (None before init_node)."""
    reg = _reg_manager()
    return reg.master_uri if reg is not None else None


def register_again():
    """Register this node's remaining topics and services with its master again. rospy registers
    them once, when each is made; after the master has been replaced by a new one at the same URI
    (a world launched again), rospy's own /rosout and /clock would otherwise stay unknown to it."""
    from rospy.impl.registration import get_service_manager, get_topic_manager

    reg = _reg_manager()
    master = xmlrpc.client.ServerProxy(reg.master_uri)
    me = rospy.get_name()
    for name, type_name in get_topic_manager().get_publications():
        master.registerPublisher(me, name, type_name, reg.uri)
    for name, type_name in get_topic_manager().get_subscriptions():
        code, _, publishers = master.registerSubscriber(me, name, type_name, reg.uri)
        if code == 1:
            reg.publisher_update(name, publishers)
    for name, uri in get_service_manager().get_services():
        master.registerService(me, name, uri, reg.uri)


def master_online(uri):
    """True when a ROS master answers at `uri`."""
    return rosgraph.Master("/unexmin_probe", master_uri=uri).is_online()
