"""The bind shim's rules (cpp/bind_shim/bind_shim.c, docs/reliability.md "Safe by default"), on a small program with
libunexmin_bind_shim.so preloaded: a wildcard bind() of a TCP or UDP socket, IPv4 or IPv6, and a listen() on a
socket never bound end up on the address ROS_IP / ROS_HOSTNAME names (127.0.0.1 when neither is set); a bind() to a
given address, or of another family, is left alone; an address that cannot be used fails the bind with one line on
stderr, never a wider bind. Each program runs in an empty network namespace of its own (root) with an /etc/hosts
of the test's: no traffic leaves it, and host names resolve the same on every machine."""

import errno
import json
import os
import subprocess

import pytest

from unexmin.bind_shim import advertised_host, library_path, ros_environment

PROGRAM = r"""
import json, os, socket
out = {}
def attempt(key, family, kind, address):
    s = socket.socket(family, kind)
    try:
        s.listen() if address is None else s.bind(address)
        name = s.getsockname()
        out[key] = name[0] if isinstance(name, tuple) else name == address.encode()  # AF_UNIX: its own name
    except OSError as e:
        out[key] = e.errno
attempt("tcp4", socket.AF_INET, socket.SOCK_STREAM, ("0.0.0.0", 0))
attempt("udp4", socket.AF_INET, socket.SOCK_DGRAM, ("", 0))
attempt("tcp6", socket.AF_INET6, socket.SOCK_STREAM, ("::", 0))
attempt("listen4", socket.AF_INET, socket.SOCK_STREAM, None)
attempt("given", socket.AF_INET, socket.SOCK_STREAM, ("127.0.0.2", 0))
attempt("unix", socket.AF_UNIX, socket.SOCK_STREAM, "\0unexmin-bind-shim-test-%d" % os.getpid())
print(json.dumps(out))
"""
HOSTS = "127.0.0.1 localhost\n::1 localhost\n127.0.0.7 ux-test-host\n::1 ux-test-host6\n"
UNAVAILABLE = errno.EADDRNOTAVAIL


def run(tmp_path, **names):
    """(the program's results, its stderr) with the shim preloaded and the environment variables `names`."""
    if os.geteuid() != 0:
        pytest.skip("an empty network namespace and a private /etc/hosts need root")
    (tmp_path / "hosts").write_text(HOSTS)
    env = {k: v for k, v in os.environ.items() if k not in ("ROS_IP", "ROS_HOSTNAME", "LD_PRELOAD")}
    env.update(names, LD_PRELOAD=library_path())
    inside = 'ip link set lo up && mount --bind "$0" /etc/hosts && exec /usr/bin/python3 -c "$1"'
    run = subprocess.run(
        ["unshare", "--mount", "--net", "sh", "-c", inside, str(tmp_path / "hosts"), PROGRAM],
        capture_output=True,
        text=True,
        timeout=30,
        env=env,
    )
    assert run.returncode == 0, run.stderr
    return json.loads(run.stdout), run.stderr


def expect(v4, v6):
    """The program's results when wildcard binds go to `v4` (IPv4) and `v6` (IPv6), an errno where they fail."""
    return {"tcp4": v4, "udp4": v4, "tcp6": v6, "listen4": v4, "given": "127.0.0.2", "unix": True}


@pytest.mark.parametrize(
    "names, result",
    [
        ({}, expect("127.0.0.1", "::ffff:127.0.0.1")),
        ({"ROS_IP": "127.0.0.5"}, expect("127.0.0.5", "::ffff:127.0.0.5")),
        ({"ROS_IP": "::1"}, expect("127.0.0.1", "::1")),
        ({"ROS_HOSTNAME": "localhost"}, expect("127.0.0.1", "::ffff:127.0.0.1")),
        ({"ROS_HOSTNAME": "ux-test-host"}, expect("127.0.0.7", "::ffff:127.0.0.7")),  # resolved (the test's hosts)
        (
            {"ROS_IP": "127.0.0.6", "ROS_HOSTNAME": "ux-test-host"},
            expect("127.0.0.6", "::ffff:127.0.0.6"),
        ),  # ROS_IP first
    ],
    ids=["default", "ros_ip", "ros_ip_v6_loopback", "localhost", "hostname", "ros_ip_before_hostname"],
)
def test_wildcard_binds_go_to_the_address_asked(tmp_path, names, result):
    got, stderr = run(tmp_path, **names)
    assert got == result
    assert stderr == ""


def test_an_address_of_no_interface_fails_the_bind_with_one_line(tmp_path):
    got, stderr = run(tmp_path, ROS_IP="192.0.2.1")  # TEST-NET-1: on no interface of the namespace
    assert got == expect(UNAVAILABLE, UNAVAILABLE)
    assert stderr.splitlines() == [
        "unexmin bind shim: cannot listen on ROS_IP='192.0.2.1': Cannot assign requested "
        "address: expected ROS_IP (or ROS_HOSTNAME) naming an address of this machine"
    ]


def test_a_host_name_that_does_not_resolve_fails_the_bind_with_one_line(tmp_path):
    got, stderr = run(tmp_path, ROS_HOSTNAME="ux-no-such-host.invalid")
    assert got == expect(UNAVAILABLE, UNAVAILABLE)
    assert stderr.splitlines() == [
        "unexmin bind shim: no IPv4 address for ROS_HOSTNAME='ux-no-such-host.invalid': "
        "expected ROS_IP (or ROS_HOSTNAME) naming an address of this machine"
    ]


def test_an_ipv6_only_name_leaves_ipv4_sockets_unbound(tmp_path):
    got, stderr = run(tmp_path, ROS_HOSTNAME="ux-test-host6")
    assert got == expect(UNAVAILABLE, "::1")
    assert "no IPv4 address for ROS_HOSTNAME='ux-test-host6'" in stderr and len(stderr.splitlines()) == 1


def test_ros_environment_defaults_to_the_loopback_and_preloads_the_shim_once():
    env = ros_environment({"LD_LIBRARY_PATH": os.path.dirname(library_path()), "LD_PRELOAD": "libother.so"})
    assert env["ROS_IP"] == "127.0.0.1"
    assert env["LD_PRELOAD"] == f"{library_path()} libother.so"
    assert ros_environment(dict(env))["LD_PRELOAD"] == env["LD_PRELOAD"]
    asked = ros_environment({"LD_LIBRARY_PATH": os.path.dirname(library_path()), "ROS_HOSTNAME": "robot"})
    assert "ROS_IP" not in asked and advertised_host(asked) == "robot"
    assert advertised_host({"ROS_IP": "fd00::2"}) == "[fd00::2]"
    with pytest.raises(FileNotFoundError, match="libunexmin_bind_shim.so is in none of"):
        library_path({"LD_LIBRARY_PATH": "/nonexistent", "CMAKE_PREFIX_PATH": ""})
