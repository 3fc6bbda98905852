#!/usr/bin/python3
"""Saves the Nth message of a sensor_msgs/Image topic (rgb8 or bgr8) as a PNG, for the debug-image
pictures of docs/ros.md (scripts/ros-debug-image.sh). Pure Python (zlib), no OpenCV needed.
Usage: ros-debug-image.py TOPIC OUT.png [N (default 5)] [TIMEOUT_S (default 60)]"""
import os
import struct
import sys
import zlib

import rospy

# Debian ships no python3 sensor_msgs: the message is read as rospy.AnyMsg and decoded here
# (the ROS 1 wire format of sensor_msgs/Image: header, height, width, encoding, is_bigendian,
# step, data; little-endian, strings and arrays prefixed by a uint32 length).


class RawImage:
    def __init__(self, buff):
        off = 12  # header: seq, stamp.secs, stamp.nsecs
        n, = struct.unpack_from('<I', buff, off)
        off += 4 + n  # frame_id
        self.height, self.width = struct.unpack_from('<II', buff, off)
        off += 8
        n, = struct.unpack_from('<I', buff, off)
        self.encoding = bytes(buff[off + 4:off + 4 + n]).decode()
        off += 4 + n + 1  # encoding, is_bigendian
        self.step, n = struct.unpack_from('<II', buff, off)
        off += 8
        self.data = bytes(buff[off:off + n])


def write_png(path, width, height, rows):
    def chunk(kind, data):
        body = kind + data
        return struct.pack('>I', len(data)) + body + struct.pack('>I', zlib.crc32(body) & 0xffffffff)
    raw = b''.join(b'\x00' + r for r in rows)
    png = b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', width, height, 8, 2, 0, 0, 0))
    png += chunk(b'IDAT', zlib.compress(raw, 9)) + chunk(b'IEND', b'')
    tmp = path + '.tmp'
    with open(tmp, 'wb') as f:
        f.write(png)
    os.replace(tmp, path)  # never a half-written picture under the final name


def main():
    topic, out = sys.argv[1], sys.argv[2]
    want = int(sys.argv[3]) if len(sys.argv) > 3 else 5
    timeout = float(sys.argv[4]) if len(sys.argv) > 4 else 60.0
    rospy.init_node('cropsight_debug_image', anonymous=True)
    seen = [0]

    def on_image(raw):
        m = RawImage(raw._buff)
        seen[0] += 1
        if seen[0] != want:
            return
        if m.encoding not in ('rgb8', 'bgr8'):
            rospy.logerr('%s: encoding %s, expected rgb8 or bgr8', topic, m.encoding)
            rospy.signal_shutdown('bad encoding')
            return
        rows = []
        for v in range(m.height):
            row = bytes(m.data[v * m.step: v * m.step + 3 * m.width])
            if m.encoding == 'bgr8':
                row = b''.join(row[i:i + 3][::-1] for i in range(0, len(row), 3))
            rows.append(row)
        write_png(out, m.width, m.height, rows)
        print('%s: message %d (%dx%d) -> %s' % (topic, want, m.width, m.height, out))
        rospy.signal_shutdown('done')

    rospy.Subscriber(topic, rospy.AnyMsg, on_image, queue_size=10)
    deadline = rospy.Time.now() + rospy.Duration(timeout)
    while not rospy.is_shutdown() and rospy.Time.now() < deadline:
        rospy.sleep(0.1)
    if seen[0] < want:
        sys.exit('%s: %d of %d messages within %.0f s' % (topic, seen[0], want, timeout))


if __name__ == '__main__':
    main()
