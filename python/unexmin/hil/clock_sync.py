"""Clock offset between two hosts from a four-timestamp exchange (as NTP does), over UDP; no ROS.

The client sends its time t1; the server stamps the arrival t2 and the departure t3 with its own clock and sends
the three back; the client stamps the arrival t4. With a path of the same delay both ways,

    offset = ((t2 - t1) + (t3 - t4)) / 2      (server clock - client clock) [s]
    delay  = (t4 - t1) - (t3 - t2)            (the round trip on the wire) [s]

and the sample with the smallest delay is the one least disturbed by queueing. Both clocks are the wall clock
(time.time()), the clock message stamps are read from.
"""

import socket
import struct
import threading
import time

# Request: t1. Reply: t1, t2, t3. Doubles, network byte order.
_REQUEST = struct.Struct("!d")
_REPLY = struct.Struct("!ddd")


def offset_and_delay(t1, t2, t3, t4):
    """(offset, delay) [s] of one exchange: offset = server clock - client clock, delay = the round trip less the
    server's time between receiving and answering."""
    return ((t2 - t1) + (t3 - t4)) / 2.0, (t4 - t1) - (t3 - t2)


class TimeServer:
    """Answers four-timestamp requests on UDP `address`:`port` (port 0: one chosen by the system, see .port) from a
    thread of its own, until close()."""

    def __init__(self, address, port=0, clock=time.time):
        self.clock = clock
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        try:
            self.sock.bind((address, port))
        except OSError as e:
            self.sock.close()
            raise OSError(
                f"time server: cannot listen on UDP {address}:{port}: {e.strerror}: expected an address "
                "of this machine and a free port"
            ) from e
        self.sock.settimeout(0.2)
        self.port = self.sock.getsockname()[1]
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._serve, name="time_server", daemon=True)
        self._thread.start()

    def _serve(self):
        while not self._stop.is_set():
            try:
                data, peer = self.sock.recvfrom(64)
            except socket.timeout:
                continue
            except OSError:  # closed
                return
            t2 = self.clock()
            if len(data) != _REQUEST.size:
                continue  # not a request of ours
            (t1,) = _REQUEST.unpack(data)
            try:
                self.sock.sendto(_REPLY.pack(t1, t2, self.clock()), peer)
            except OSError:  # the link went away meanwhile: the client times out and asks again
                pass

    def close(self):
        self._stop.set()
        self._thread.join(2.0)
        self.sock.close()


def measure_offset(address, port, samples=20, timeout=1.0, clock=time.time):
    """Exchange `samples` requests with the TimeServer at `address`:`port`; return a dict with the offset [s]
    (server clock - this host's clock) and delay [s] of the exchange of smallest delay, and every sample's
    (offset, delay). TimeoutError names the server when no answer comes within `timeout` [s] of a request,
    ConnectionRefusedError when its host says nothing listens there."""
    if samples < 1:
        raise ValueError(f"samples = {samples!r}: expected at least 1")
    found = []
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as sock:
        sock.settimeout(timeout)
        sock.connect((address, port))  # connected: the host's "nothing listens here" comes back as an error
        for _ in range(samples):
            t1 = clock()
            sock.send(_REQUEST.pack(t1))
            while True:
                try:
                    data = sock.recv(64)
                except socket.timeout:
                    raise TimeoutError(
                        f"no answer from the time server at {address}:{port} (UDP) within " f"{timeout:g} s"
                    ) from None
                except ConnectionRefusedError:  # the host said nothing listens on that port
                    raise ConnectionRefusedError(
                        f"no time server at {address}:{port} (UDP): the host refused; is "
                        "the stand-in started with --time-port?"
                    ) from None
                t4 = clock()
                if len(data) == _REPLY.size and _REPLY.unpack(data)[0] == t1:
                    break  # not a late answer to an earlier request
            found.append(offset_and_delay(t1, *_REPLY.unpack(data)[1:], t4))
    best = min(found, key=lambda s: s[1])
    return {"offset": best[0], "delay": best[1], "samples": found}
