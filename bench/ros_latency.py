#!/usr/bin/python3
"""Latency client of bench/ros_latency.sh: for each cloud on --input (stamped by the publisher when it is
sent), the time until the resampled cloud with the same stamp has arrived here from --node's ~output, and
the size of the model on ~model against the input PointCloud2's data. Prints one line per frame and a
summary; exit 2 when the node reports that it cannot encode clouds (no point-cloud input yet)."""

import argparse
import statistics
import sys
import threading
import time

import rospy
from rosgraph_msgs.msg import Log
from sensor_msgs.msg import PointCloud2
from std_msgs.msg import UInt8MultiArray


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--input", required=True)
    parser.add_argument("--node", required=True)
    parser.add_argument("--frames", type=int, default=10)
    parser.add_argument("--timeout", type=float, default=120.0)
    args = parser.parse_args(rospy.myargv()[1:])
    rospy.init_node("pcl_sparse_latency", anonymous=True, disable_signals=True)

    lock = threading.Condition()
    state = {"input_bytes": 0, "input_shape": "", "latencies": [], "points": 0, "models": [], "error": None}

    def on_input(msg):
        with lock:
            state["input_bytes"] = len(msg.data)
            state["input_shape"] = "%dx%d, %s" % (msg.width, msg.height, " ".join(f.name for f in msg.fields))
            lock.notify_all()
        input_sub.unregister()  # one is enough: the publisher sends the same cloud again and again

    def on_output(msg):
        arrived = rospy.Time.now()
        with lock:
            state["latencies"].append((arrived - msg.header.stamp).to_sec())
            state["points"] = msg.width * msg.height
            lock.notify_all()

    def on_model(msg):
        with lock:
            state["models"].append(len(msg.data))

    def on_log(msg):
        if msg.level >= Log.ERROR and msg.msg.startswith("[%s]" % args.node):
            with lock:
                state["error"] = msg.msg
                lock.notify_all()

    rospy.Subscriber("/rosout_agg", Log, on_log)
    input_sub = rospy.Subscriber(args.input, PointCloud2, on_input, queue_size=1)
    rospy.Subscriber(args.node + "/output", PointCloud2, on_output, queue_size=5, tcp_nodelay=True)
    rospy.Subscriber(args.node + "/model", UInt8MultiArray, on_model, queue_size=5, tcp_nodelay=True)

    wanted = args.frames + 1  # the first frame (connections, first allocations) is not counted
    deadline = time.time() + args.timeout
    with lock:
        while len(state["latencies"]) < wanted and state["error"] is None and time.time() < deadline:
            lock.wait(0.5)
            if state["latencies"]:
                deadline = max(deadline, time.time() + args.timeout)
    if state["error"] is not None and not state["latencies"]:
        print("CANNOT MEASURE: %s cannot encode the cloud: %s" % (args.node, state["error"][len(args.node) + 3:]))
        if "has no polygons" in state["error"]:
            print("(the encoder does not take clouds without polygons yet: this bench works once point-cloud "
                  "input lands)")
        return 2
    latencies = state["latencies"][1:]
    if not latencies:
        print("CANNOT MEASURE: no resampled cloud from %s within %g s" % (args.node, args.timeout))
        return 1
    for i, latency in enumerate(latencies):
        print("frame %d: %.3f s" % (i + 1, latency))
    model = statistics.median(state["models"]) if state["models"] else 0
    ratio = model / state["input_bytes"] if state["input_bytes"] else float("nan")
    print("input: %s, %d bytes of point data" % (state["input_shape"], state["input_bytes"]))
    print("output: %d points" % state["points"])
    print("latency (PointCloud2 in -> resampled PointCloud2 out, through roscore): median %.3f s, max %.3f s "
          "over %d frames: %s (target 1 s)" % (statistics.median(latencies), max(latencies), len(latencies),
                                              "PASS" if max(latencies) <= 1.0 else "MISS"))
    print("model message: %d bytes = %.2f %% of the input (target at most 5 %%): %s"
          % (model, 100 * ratio, "PASS" if ratio <= 0.05 else "MISS"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
