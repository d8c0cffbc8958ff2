// Validates one .gltf/.glb with the Khronos glTF validator (the version pinned in
// package-lock.json beside this file). Prints the issue counts and every issue.
// Exit status: 0 clean, 1 errors (with --strict also warnings), 2 could not validate.
//
// Usage: node validate.mjs FILE [--strict]
// GLTF_VALIDATOR_PREFIX names the folder whose node_modules holds gltf-validator
// (scripts/validate-gltf.sh installs it there); default: this script's folder.
import { readFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { basename, dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const args = process.argv.slice(2);
const strict = args.includes('--strict');
const files = args.filter((a) => a !== '--strict');
if (files.length !== 1) {
  console.error('usage: node validate.mjs FILE.glb [--strict]');
  process.exit(2);
}
const file = files[0];

const prefix = process.env.GLTF_VALIDATOR_PREFIX || dirname(fileURLToPath(import.meta.url));
let validator;
try {
  validator = createRequire(join(prefix, 'package.json'))('gltf-validator');
} catch (e) {
  console.error(`error: gltf-validator is not installed under ${prefix} (${e.message}); ` +
                'run scripts/validate-gltf.sh, which installs it');
  process.exit(2);
}

let bytes;
try {
  bytes = readFileSync(file);
} catch (e) {
  console.error(`error: ${file}: ${e.message}`);
  process.exit(2);
}

const severities = ['error', 'warning', 'info', 'hint'];
let report;
try {
  report = await validator.validateBytes(new Uint8Array(bytes), {
    uri: basename(file),
    maxIssues: 0,  // all of them
    writeTimestamp: false,
  });
} catch (e) {
  console.error(`error: ${file}: the validator could not read it: ${e}`);
  process.exit(2);
}

const issues = report.issues;
console.log(`${file}: ${issues.numErrors} errors, ${issues.numWarnings} warnings, ` +
            `${issues.numInfos} infos, ${issues.numHints} hints ` +
            `(gltf-validator ${validator.version()})`);
const info = report.info || {};
console.log(`  ${info.animationCount ?? 0} animations, skins: ${info.hasSkins ? 'yes' : 'no'}, ` +
            `max influences ${info.maxInfluences ?? 0}, ` +
            `${info.materialCount ?? '?'} materials, ${info.drawCallCount ?? '?'} draw calls, ` +
            `${info.totalVertexCount ?? '?'} vertices, ${info.totalTriangleCount ?? '?'} triangles`);
for (const m of issues.messages) {
  const where = m.pointer ?? (m.offset !== undefined ? `byte ${m.offset}` : '');
  console.log(`  ${severities[m.severity] ?? m.severity} ${m.code} ${where}: ${m.message}`);
}
const failed = issues.numErrors > 0 || (strict && issues.numWarnings > 0);
process.exit(failed ? 1 : 0);
