"""python-can's slcan client against the simulated slcan top
(controller/tests/slcan_pty.rs runs this with the pseudo-terminal's path).

It opens can.Bus(interface='slcan', bitrate=500000) on the terminal (python-can
sends C, S6, an empty line and O), sends a standard, an extended, a standard
remote and an extended remote frame, prints SENT, then waits for the frames
the other simulated nodes send (EXPECTED below, in this order) and prints
each as "RX <id> <ext> <rtr> <dlc> <data hex>". Exit status 0 when all
arrived as expected, 2 on a wrong frame, 4 on a timeout, 3 when python-can or
pyserial is missing.
"""
import sys
import time

try:
    import can
    import serial  # noqa: F401  (python-can's slcan interface needs it)
except ImportError as e:
    print(f"MISSING {e.name}: install with python3 -m pip install python-can pyserial", flush=True)
    sys.exit(3)

SENT = [
    can.Message(arbitration_id=0x123, data=[1, 2, 3, 4, 5, 6, 7, 8], is_extended_id=False),
    can.Message(arbitration_id=0x1ABCDEF0, data=[0xA5, 0x5A, 0x00], is_extended_id=True),
    can.Message(arbitration_id=0x7FF, dlc=2, is_remote_frame=True, is_extended_id=False),
    can.Message(arbitration_id=0x00000042, dlc=0, is_remote_frame=True, is_extended_id=True),
]
# (id, extended, remote, dlc, data)
EXPECTED = [
    (0x321, False, False, 4, bytes([0xDE, 0xAD, 0xBE, 0xEF])),
    (0x10000001, True, False, 8, bytes(range(0x10, 0x18))),
    (0x055, False, True, 1, b""),
    (0x0ABCDEF1, True, True, 0, b""),
]


def main() -> int:
    bus = can.Bus(interface="slcan", channel=sys.argv[1], bitrate=500000, sleep_after_open=0)
    try:
        for m in SENT:
            bus.send(m)
        print("SENT", flush=True)
        got = []
        deadline = time.monotonic() + float(sys.argv[2]) if len(sys.argv) > 2 else 120.0
        while len(got) < len(EXPECTED):
            left = deadline - time.monotonic()
            if left <= 0:
                print(f"TIMEOUT after {len(got)} frames", flush=True)
                return 4
            m = bus.recv(timeout=min(left, 1.0))
            if m is None:
                continue
            data = bytes(m.data) if not m.is_remote_frame else b""
            print(f"RX {m.arbitration_id:X} {int(m.is_extended_id)} {int(m.is_remote_frame)} {m.dlc} {data.hex()}", flush=True)
            got.append((m.arbitration_id, m.is_extended_id, m.is_remote_frame, m.dlc, data))
        if got != EXPECTED:
            print(f"WRONG {got!r}", flush=True)
            return 2
        print("OK", flush=True)
        return 0
    finally:
        bus.shutdown()


if __name__ == "__main__":
    sys.exit(main())
