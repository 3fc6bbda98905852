#pragma once
// The broccoli report's data (broccoli_report.hpp) from what the library's tracking evaluator
// measured: curves, map, sizes, key figures and the overlay pictures of the first pass.
#include "cropsight/pipeline/broccoli/tracking_eval.hpp"
#include "cropsight/report/broccoli_report.hpp"

namespace cropsight::report {

/// One frame's picture: depth colours (render.hpp's map, chosen so that heads stand out from the
/// soil), heads that reached the map green, the others red, predicted points of mapped heads
/// magenta, the ground-truth outlines on top when the overlay has labels.
ColorImage broccoli_overlay(const pipeline::broccoli::PassMaterial::Overlay& overlay);

/// Everything but `model` and `stages`, which the caller knows. Overlays: depth colours, heads
/// that reached the map green, the others red, predicted points of mapped heads magenta, the
/// ground-truth outlines on top.
BroccoliReportData broccoli_report_data(const pipeline::broccoli::TrackingFigures& figures,
                                        const pipeline::broccoli::PassMaterial& material);

}  // namespace cropsight::report
