// Checks a .glb with the Khronos glTF validator: exit 0 when it reports no errors.
// Usage: node check_glb.mjs FILE.glb
import { readFile } from "node:fs/promises";
import validator from "gltf-validator";

const file = process.argv[2];
const bytes = new Uint8Array(await readFile(file));
const report = await validator.validateBytes(bytes, { uri: file, maxIssues: 50 });
const { numErrors, numWarnings, messages } = report.issues;
for (const m of messages) if (m.severity <= 1) console.log(`${m.severity === 0 ? "error" : "warning"}: ${m.code} ${m.message} at ${m.pointer ?? ""}`);
const info = report.info ?? {};
console.log(`${file}: ${numErrors} errors, ${numWarnings} warnings; ${info.drawCallCount ?? "?"} draw calls, ${info.totalVertexCount ?? "?"} vertices, ${info.totalTriangleCount ?? "?"} triangles`);
process.exit(numErrors === 0 ? 0 : 1);
