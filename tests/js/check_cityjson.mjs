// Checks an exacity city.city.json: every vertex index in range, no ring repeating a
// vertex, every Solid's shell closed (each edge used once in each direction) after
// quantisation, every geometry instance naming a template that exists; and, given the
// CityJSON 2.0 JSON schemas' folder, against the schemas (with Ajv).
// Usage: node check_cityjson.mjs CITY_JSON [SCHEMA_DIR]   (exit 0 when everything holds)
import { readFileSync, readdirSync } from "node:fs";
import { join } from "node:path";
import Ajv from "ajv";

const [cityFile, schemaDir] = process.argv.slice(2);
const city = JSON.parse(readFileSync(cityFile, "utf8"));
const problems = [];
if (schemaDir) {
  const ajv = new Ajv({ strict: false, validateFormats: false, allErrors: false });
  let main;
  for (const f of readdirSync(schemaDir).filter((f) => f.endsWith(".schema.json"))) {
    const schema = JSON.parse(readFileSync(join(schemaDir, f), "utf8"));
    ajv.addSchema(schema);
    if (f === "cityjson.schema.json") main = schema.$id;
  }
  const validate = ajv.getSchema(main);
  if (!validate(city)) for (const e of validate.errors.slice(0, 10)) problems.push(`schema: ${e.message} at ${e.instancePath}`);
}

const n = city.vertices.length;
const templates = city["geometry-templates"]?.templates ?? [];
function* rings(b) {
  if (b.length && typeof b[0] === "number") yield b;
  else for (const x of b) yield* rings(x);
}
for (const [id, obj] of Object.entries(city.CityObjects)) {
  for (const g of obj.geometry ?? []) {
    if (g.type === "GeometryInstance") {
      if (!(g.template >= 0 && g.template < templates.length)) problems.push(`${id}: no template ${g.template}`);
      if (!(g.boundaries[0] >= 0 && g.boundaries[0] < n)) problems.push(`${id}: reference point out of range`);
      continue;
    }
    for (const r of rings(g.boundaries)) {
      if (r.some((i) => i < 0 || i >= n)) problems.push(`${id}: vertex index out of range`);
      if (r.length < 3 || new Set(r).size !== r.length) problems.push(`${id}: a ring repeats a vertex or has under 3`);
    }
    if (g.type === "Solid") {
      const edges = new Map();
      for (const surface of g.boundaries[0])
        for (const r of surface)
          r.forEach((a, k) => {
            const key = `${a},${r[(k + 1) % r.length]}`;
            edges.set(key, (edges.get(key) ?? 0) + 1);
          });
      for (const [key, count] of edges) {
        const [a, b] = key.split(",");
        if ((edges.get(`${b},${a}`) ?? 0) !== count) {
          problems.push(`${id}: lod ${g.lod} shell is not closed`);
          break;
        }
      }
    }
  }
}
for (const p of problems.slice(0, 20)) console.log("problem:", p);
const checked = schemaDir ? "schemas and content" : "content only, no schemas";
console.log(`${cityFile}: ${Object.keys(city.CityObjects).length} city objects, ${n} vertices (${checked}), ${problems.length ? problems.length + " problems" : "ok"}`);
process.exit(problems.length ? 1 : 0);
