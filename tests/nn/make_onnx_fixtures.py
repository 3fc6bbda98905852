#!/usr/bin/env python3
"""Writes the tiny ONNX detectors that tests/nn/test_onnx_detector.cpp decodes.

Usage: make_onnx_fixtures.py OUT_DIR

Every graph takes an image blob `images` [1, 3, H, W] and returns a table chosen by hand: the
input is reshaped to a fixed total (so a network fed the wrong input size fails, as a real
fixed-shape export does), averaged to [1, 3, 1, 1], multiplied by zero weights in a 1x1
convolution whose bias is the table, and reshaped to the layout. The output is therefore exactly
the table for any finite input, and the decoder's letterbox undo, threshold and NMS can be
checked against boxes computed by hand. Needs Debian's python3-onnx (onnx.helper), opset 12.
"""
import sys

import numpy as np
import onnx
from onnx import TensorProto, helper, numpy_helper

OPSET = 12
W, H = 64, 64  # network input size of every fixture

# YOLOv5 rows: cx, cy, w, h (input pixels), objectness, class scores (potato, sprout).
YOLOV5 = [
    [32, 32, 16, 8, 0.9, 0.8, 0.1],  # kept: potato 0.72
    [33, 32, 16, 8, 0.8, 0.5, 0.2],  # potato 0.40, IoU 0.88 with row 0: suppressed
    [32, 32, 16, 8, 0.9, 0.1, 0.7],  # sprout 0.63, same box as row 0: kept (NMS per class)
    [20, 20, 8, 8, 0.5, 0.4, 0.0],  # potato 0.20 < 0.25: dropped
    [10, 12, 8, 12, 1.0, 0.6, 0.0],  # potato 0.60, reaches into the top pad: clipped
    [50, 40, 10, 10, 0.3, 0.9, 0.0],  # potato 0.27: kept
]

# SSD DetectionOutput rows: image_id, label, confidence, x1, y1, x2, y2 (normalised to the input).
SSD = [
    [0, 0, 0.9, 0.25, 0.25, 0.5, 0.5],
    [0, 0, 0.8, 0.26, 0.25, 0.51, 0.5],  # IoU 0.92 with row 0: suppressed
    [0, 1, 0.7, 0.25, 0.25, 0.5, 0.5],  # other class: kept
    [0, 0, 0.1, 0.0, 0.0, 1.0, 1.0],  # below threshold
    [0, 0, 0.5, 0.75, 0.5, 1.0, 0.75],
]


def finish(graph):
    """The checked model of `graph`: opset 12, IR version 7 (what OpenCV 4.6 reads)."""
    model = helper.make_model(graph, opset_imports=[helper.make_opsetid("", OPSET)], producer_name="cropsight-tests")
    model.ir_version = 7
    onnx.checker.check_model(model)
    return model


def table_graph(name, table, out_shape):
    """A graph returning `table` (reshaped to out_shape) for any [1, 3, H, W] input."""
    table = np.asarray(table, dtype=np.float32)
    k = table.size
    inits = [
        numpy_helper.from_array(np.array([1, 3, H * W, 1], dtype=np.int64), "flat_shape"),
        numpy_helper.from_array(np.zeros((k, 3, 1, 1), dtype=np.float32), "zero_w"),
        numpy_helper.from_array(table.reshape(-1), "table"),
        numpy_helper.from_array(np.array(out_shape, dtype=np.int64), "out_shape"),
    ]
    nodes = [
        helper.make_node("Reshape", ["images", "flat_shape"], ["flat"]),
        helper.make_node("GlobalAveragePool", ["flat"], ["pooled"]),
        helper.make_node("Conv", ["pooled", "zero_w", "table"], ["conv"], kernel_shape=[1, 1]),
        helper.make_node("Reshape", ["conv", "out_shape"], ["output"]),
    ]
    graph = helper.make_graph(
        nodes, name,
        [helper.make_tensor_value_info("images", TensorProto.FLOAT, [1, 3, H, W])],
        [helper.make_tensor_value_info("output", TensorProto.FLOAT, list(out_shape))],
        inits)
    return finish(graph)


def channel_means():
    """yolov5 layout, 3 rows: row k scores the mean of blob channel k (objectness 1, class score
    = that mean), boxes far apart so NMS keeps all three. Checks letterbox, channel order, mean
    and scale of the input blob."""
    k = 3 * 7
    w = np.zeros((k, 3, 1, 1), dtype=np.float32)
    b = np.zeros(k, dtype=np.float32)
    for row in range(3):
        b[row * 7:row * 7 + 5] = [8 + 20 * row, 8, 8, 8, 1]
        w[row * 7 + 5, row, 0, 0] = 1
    inits = [numpy_helper.from_array(w, "w"), numpy_helper.from_array(b, "b"),
             numpy_helper.from_array(np.array([1, 3, 7], dtype=np.int64), "out_shape")]
    nodes = [
        helper.make_node("GlobalAveragePool", ["images"], ["pooled"]),
        helper.make_node("Conv", ["pooled", "w", "b"], ["conv"], kernel_shape=[1, 1]),
        helper.make_node("Reshape", ["conv", "out_shape"], ["output"]),
    ]
    graph = helper.make_graph(
        nodes, "channel_means",
        [helper.make_tensor_value_info("images", TensorProto.FLOAT, [1, 3, H, W])],
        [helper.make_tensor_value_info("output", TensorProto.FLOAT, [1, 3, 7])], inits)
    return finish(graph)


# YOLOv8 head rows: anchor (x, y) in grid cells, stride, DFL bin of each distance (l, t, r, b),
# class logits. Box: centre = (anchor + ((r - l) / 2, (b - t) / 2)) x stride,
# size = (l + r, t + b) x stride; scores = sigmoid(logits).
YOLOV8_HEAD = [
    [4.5, 4.5, 8, (2, 1, 2, 1), (2.0, -4.0)],  # centre (36, 36), size 32 x 16, potato 0.881
    [1.5, 2.5, 16, (1, 1, 3, 1), (-4.0, 1.0)],  # centre (40, 40), size 64 x 32, sprout 0.731
    [0.5, 0.5, 32, (0, 0, 1, 1), (-5.0, -5.0)],  # both scores 0.0067: below any useful threshold
]
REG_MAX = 16


def yolov8_head(full_strides):
    """The head of a YOLOv8 export with its anchors and strides folded to constants (what
    onnx-simplifier or a static export leaves), opset 12 (Split sizes as an attribute): DFL
    (Reshape, Transpose, Softmax, 1x1 Conv with weights 0..15), dist2bbox (Split, Sub, Add, Div,
    Concat), Mul by strides, Sigmoid of the class logits, Concat → [1, 4 + C, N].
    full_strides False: strides [1, N] as ultralytics exports them (`dbox * self.strides`,
    broadcast over the 4 box channels); True: strides repeated to [1, 4, N]."""
    n, c = len(YOLOV8_HEAD), len(YOLOV8_HEAD[0][4])
    raw = np.zeros((4 * REG_MAX + c, n), dtype=np.float32)
    anchors = np.zeros((1, 2, n), dtype=np.float32)
    strides = np.zeros((1, n), dtype=np.float32)
    for i, (ax, ay, stride, bins, logits) in enumerate(YOLOV8_HEAD):
        for side, b in enumerate(bins):
            raw[side * REG_MAX + b, i] = 30.0  # softmax puts all weight on bin b
        raw[4 * REG_MAX:, i] = logits
        anchors[0, :, i] = (ax, ay)
        strides[0, i] = stride
    k = raw.size
    inits = [
        numpy_helper.from_array(np.array([1, 3, H * W, 1], dtype=np.int64), "flat_shape"),
        numpy_helper.from_array(np.zeros((k, 3, 1, 1), dtype=np.float32), "zero_w"),
        numpy_helper.from_array(raw.reshape(-1), "raw"),
        numpy_helper.from_array(np.array([1, 4 * REG_MAX + c, n], dtype=np.int64), "raw_shape"),
        numpy_helper.from_array(np.array([1, 4, REG_MAX, n], dtype=np.int64), "dfl_shape"),
        numpy_helper.from_array(np.arange(REG_MAX, dtype=np.float32).reshape(1, REG_MAX, 1, 1), "dfl_w"),
        numpy_helper.from_array(np.array([1, 4, n], dtype=np.int64), "dist_shape"),
        numpy_helper.from_array(anchors, "anchors"),
        numpy_helper.from_array(np.array([2.0], dtype=np.float32), "two"),
        numpy_helper.from_array(np.repeat(strides[:, None, :], 4, axis=1) if full_strides else strides, "strides"),
    ]
    nodes = [
        helper.make_node("Reshape", ["images", "flat_shape"], ["flat"]),
        helper.make_node("GlobalAveragePool", ["flat"], ["pooled"]),
        helper.make_node("Conv", ["pooled", "zero_w", "raw"], ["conv"], kernel_shape=[1, 1]),
        helper.make_node("Reshape", ["conv", "raw_shape"], ["head"]),
        helper.make_node("Split", ["head"], ["box", "cls"], axis=1, split=[4 * REG_MAX, c]),
        helper.make_node("Reshape", ["box", "dfl_shape"], ["box4"]),
        helper.make_node("Transpose", ["box4"], ["box_t"], perm=[0, 2, 1, 3]),
        helper.make_node("Softmax", ["box_t"], ["box_sm"], axis=1),
        helper.make_node("Conv", ["box_sm", "dfl_w"], ["dfl"], kernel_shape=[1, 1]),
        helper.make_node("Reshape", ["dfl", "dist_shape"], ["dist"]),
        helper.make_node("Split", ["dist"], ["lt", "rb"], axis=1, split=[2, 2]),
        helper.make_node("Sub", ["anchors", "lt"], ["x1y1"]),
        helper.make_node("Add", ["anchors", "rb"], ["x2y2"]),
        helper.make_node("Add", ["x1y1", "x2y2"], ["sum"]),
        helper.make_node("Div", ["sum", "two"], ["c_xy"]),
        helper.make_node("Sub", ["x2y2", "x1y1"], ["wh"]),
        helper.make_node("Concat", ["c_xy", "wh"], ["dbox_cells"], axis=1),
        helper.make_node("Mul", ["dbox_cells", "strides"], ["dbox"]),
        helper.make_node("Sigmoid", ["cls"], ["scores"]),
        helper.make_node("Concat", ["dbox", "scores"], ["output"], axis=1),
    ]
    graph = helper.make_graph(
        nodes, "yolov8_head",
        [helper.make_tensor_value_info("images", TensorProto.FLOAT, [1, 3, H, W])],
        [helper.make_tensor_value_info("output", TensorProto.FLOAT, [1, 4 + c, n])], inits)
    return finish(graph)


def yolov8_const_add():
    """The head of an ultralytics YOLOv8 export as OpenCV 4.6 users report it failing: anchor
    coordinates made by adding two constants of different shapes (arange + 0.5 offset)."""
    inits = [
        numpy_helper.from_array(np.arange(4, dtype=np.float32), "arange"),
        numpy_helper.from_array(np.array([0.5], dtype=np.float32), "offset"),
    ]
    nodes = [
        helper.make_node("GlobalAveragePool", ["images"], ["pooled"]),
        helper.make_node("Flatten", ["pooled"], ["flat"]),
        helper.make_node("Add", ["arange", "offset"], ["anchors"]),
        helper.make_node("Mul", ["flat", "anchors"], ["output"]),
    ]
    graph = helper.make_graph(
        nodes, "yolov8_const_add",
        [helper.make_tensor_value_info("images", TensorProto.FLOAT, [1, 3, H, W])],
        [helper.make_tensor_value_info("output", TensorProto.FLOAT, [1, 4])], inits)
    return finish(graph)


def main():
    out = sys.argv[1]
    y5 = np.asarray(YOLOV5, dtype=np.float32)
    onnx.save(table_graph("yolov5", y5, [1, len(YOLOV5), 7]), f"{out}/yolov5.onnx")
    # YOLOv8 layout: [1, 4 + C, N], no objectness; the same boxes, score = class score.
    y8 = np.concatenate([y5[:, :4], y5[:, 4:5] * y5[:, 5:]], axis=1).T.copy()
    onnx.save(table_graph("yolov8", y8, [1, 6, len(YOLOV5)]), f"{out}/yolov8.onnx")
    onnx.save(table_graph("ssd", np.asarray(SSD, dtype=np.float32), [1, 1, len(SSD), 7]), f"{out}/ssd.onnx")
    # Foreign: an output of three columns matches no layout.
    onnx.save(table_graph("foreign", np.zeros((4, 3), dtype=np.float32), [1, 4, 3]), f"{out}/foreign.onnx")
    # Damaged: the convolution's weights shorter than their shape (OpenCV 4.6 read past them;
    # found by fuzz_onnx_model). cropsight refuses the file before OpenCV reads it.
    short = table_graph("yolov5", y5, [1, len(YOLOV5), 7])
    weights = next(t for t in short.graph.initializer if len(t.dims) == 4)
    weights.raw_data = weights.raw_data[: len(weights.raw_data) // 3]
    onnx.save(short, f"{out}/short_weights.onnx")
    onnx.save(channel_means(), f"{out}/channel_means.onnx")
    onnx.save(yolov8_head(False), f"{out}/yolov8_head.onnx")
    onnx.save(yolov8_head(True), f"{out}/yolov8_head_full_strides.onnx")
    onnx.save(yolov8_const_add(), f"{out}/yolov8_const_add.onnx")


if __name__ == "__main__":
    main()
