#!/usr/bin/python3
"""Checks that the dependency definitions in msg/deps/ (which gencpp hashes into the vision_msgs
MD5 sums) hash to the MD5 sums of Debian's generated headers in /usr/include. Exit 1 on a mismatch."""
import os
import re
import sys

import genmsg
import genmsg.gentools
import genmsg.msg_loader

root = os.path.dirname(os.path.abspath(__file__))
search = {p: [os.path.join(root, 'deps', p)] for p in os.listdir(os.path.join(root, 'deps'))}
bad = 0
for pkg in sorted(search):
    for f in sorted(os.listdir(search[pkg][0])):
        name = f[:-4]
        ctx = genmsg.MsgContext.create_default()
        spec = genmsg.msg_loader.load_msg_by_type(ctx, pkg + '/' + name, search)
        genmsg.msg_loader.load_depends(ctx, spec, search)
        ours = genmsg.gentools.compute_md5(ctx, spec)
        header = open('/usr/include/%s/%s.h' % (pkg, name)).read()
        m = re.search(r'struct MD5Sum<[^{]*\{[^"]*"([0-9a-f]{32})"', header)
        debian = m.group(1) if m else None
        ok = ours == debian
        bad += not ok
        print('%-30s %s %s' % (pkg + '/' + name, ours, 'ok' if ok else 'MISMATCH (Debian: %s)' % debian))
sys.exit(1 if bad else 0)
