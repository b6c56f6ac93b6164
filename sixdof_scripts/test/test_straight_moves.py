"""The contacts a descent is allowed to make (straight_moves.AllowedContacts): the gripper with the object it takes,
the held object with the surface below it; every other contact is a collision."""

from moveit_msgs.msg import ContactInformation
from sixdof_commander.straight_moves import AllowedContacts, describe

LINK = ContactInformation.ROBOT_LINK
ATTACHED = ContactInformation.ROBOT_ATTACHED
WORLD = ContactInformation.WORLD_OBJECT


def contact(body1: str, type1: int, body2: str, type2: int, z: float = 0.0) -> ContactInformation:
    info = ContactInformation(contact_body_1=body1, contact_body_2=body2, body_type_1=type1, body_type_2=type2)
    info.position.z = z
    return info


GRASP = AllowedContacts(frozenset(["finger_left", "palm"]), frozenset(["cube"]))
PLACE = AllowedContacts(frozenset(["cube"]), below=0.005)


def test_the_gripper_may_touch_the_object_it_takes_either_way_round():
    assert GRASP.allows(contact("finger_left", LINK, "cube", WORLD))
    assert GRASP.allows(contact("cube", WORLD, "palm", LINK))


def test_other_links_on_the_object_and_the_gripper_on_other_objects_are_collisions():
    assert not GRASP.allows(contact("link4", LINK, "cube", WORLD))
    assert not GRASP.allows(contact("finger_left", LINK, "table", WORLD))
    assert not GRASP.allows(contact("link4", LINK, "table", WORLD))


def test_the_held_object_may_touch_a_surface_only_below_its_bottom():
    assert PLACE.allows(contact("cube", ATTACHED, "table", WORLD, z=0.0))
    assert PLACE.allows(contact("box_floor", WORLD, "cube", ATTACHED, z=0.004))
    assert not PLACE.allows(contact("cube", ATTACHED, "neighbour", WORLD, z=0.02))
    assert not PLACE.allows(contact("link4", LINK, "table", WORLD, z=0.0))


def test_contacts_among_the_robots_bodies_are_never_allowed_here():
    assert not PLACE.allows(contact("cube", ATTACHED, "link2", LINK, z=0.0))
    assert not AllowedContacts(frozenset(["palm"])).allows(contact("palm", LINK, "link2", LINK))


def test_nothing_is_allowed_by_default():
    assert not AllowedContacts().allows(contact("palm", LINK, "cube", WORLD))


def test_a_contact_is_described_by_its_bodies_and_height():
    assert describe(contact("link4", LINK, "table", WORLD, z=-0.0021)) == "'link4' with 'table' at z = -0.002 m"
