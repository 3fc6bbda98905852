#pragma once
// The merged field map's files (batch writes them into DIR; docs/batch.md shows examples):
//
//   field-map.csv      id,x_m,y_m,z_m[,latitude_deg,longitude_deg,altitude_m],diameter_mm,
//                      bbox_diameter_mm,hull_diameter_mm,frames_seen,passes,row,harvestable,seen_by
//                      x, y, z: the common field frame (metres); latitude/longitude/altitude (WGS84,
//                      degrees and metres) only when the recordings are geo-referenced;
//                      passes = distinct recordings that saw the head; seen_by = "SHARD#ID:FIRST-LAST"
//                      per sighting (the shard's head id and frames), separated by spaces
//   passes.csv         pass,shards,frames,heads,harvestable,shared_heads,mean_diameter_mm
//                      shared_heads = the pass's heads that another pass saw too
//   rows.csv           row,y_m,heads,harvestable,passes,mean_diameter_mm   (rows: field_merge.hpp)
//   field-map.geojson  RFC 7946 FeatureCollection of Points [lon, lat, alt] with the CSV's values
//                      as properties (QGIS and GDAL's ogrinfo read it)
#include <string>
#include <vector>

#include "cropsight/batch/field_merge.hpp"
#include "cropsight/batch/shard_runner.hpp"
#include "cropsight/io/geo_origin.hpp"

namespace cropsight::batch {

/// field-map.csv; `geo` adds the WGS84 columns (nullptr: none).
std::string merged_map_csv(const std::vector<MergedHead>& heads, const std::vector<PassMap>& maps,
                           const io::GeoReference* geo);
/// field-map.geojson.
std::string merged_map_geojson(const std::vector<MergedHead>& heads, const std::vector<PassMap>& maps,
                               const io::GeoReference& geo);
/// passes.csv from the merged heads and the shards' records (frames per pass).
std::string passes_csv(const std::vector<MergedHead>& heads, const std::vector<PassMap>& maps,
                       const std::vector<ShardRecord>& records);
/// rows.csv (heads must carry rows: assign_rows).
std::string rows_csv(const std::vector<MergedHead>& heads, const std::vector<PassMap>& maps);

}  // namespace cropsight::batch
