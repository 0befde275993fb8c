// Land use where none is mapped (docs/design.md, The sketch, GIS and OSM): the faces of the
// street network that no zone covers get a zone from the mapped buildings standing in them,
// or stay open.
#pragma once

#include <nlohmann/json.hpp>

namespace exacity {

// With the sketch's "infer_zones": true, for a document in metres whose features have their
// zones, roads and mapped buildings (after apply_osm_tags): the faces are the land the
// roads' centre lines enclose (GEOS, through OGR: the box around them less the lines grown
// by a centimetre, without what reaches the box); the part of each face no zone covers
// (under a tenth of the face is a sliver of the zones' edges, and left alone) becomes a zone
// feature appended to the document when mapped buildings have their centres in it: the
// zone their `building` tags say (houses and flats residential; shops, offices, schools
// and the like commercial; warehouses and factories industrial; an untagged `yes` by its
// size, under 500 m2 residential, else commercial), the most footprint area deciding. A face
// without any stays open. The counts go into the document's "land_use" member:
// {"street_faces", "faces_with_land_use", "inferred": {zone: faces}, "left_open"}.
void infer_zones(nlohmann::ordered_json& doc);

}  // namespace exacity
