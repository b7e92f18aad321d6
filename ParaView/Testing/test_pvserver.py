#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The plugin in client-server mode: a pvserver on 2 MPI ranks and a pvpython client
(pvserver_client.py), on a free local port.

    test_pvserver.py MPIRUN PVSERVER PVPYTHON PLUGIN DATA_DIR IMAGE
"""
import os
import socket
import subprocess
import sys

mpirun, pvserver, pvpython, plugin, data, image = sys.argv[1:7]
with socket.socket() as probe:  # a port nobody listens on
    probe.bind(("localhost", 0))
    port = probe.getsockname()[1]
server = subprocess.Popen([mpirun, "--allow-run-as-root", "--oversubscribe", "-np", "2", pvserver,
                           f"--server-port={port}"], stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, text=True)
try:
    client = subprocess.run([pvpython, os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                    "pvserver_client.py"),
                             str(port), plugin, data, image], capture_output=True, text=True,
                            timeout=240)
    print(client.stdout[-4000:])
    if client.returncode != 0:
        print(client.stderr[-4000:])
    status = client.returncode
finally:
    server.terminate()
    try:
        server.wait(timeout=30)
    except subprocess.TimeoutExpired:
        server.kill()
sys.exit(status)
