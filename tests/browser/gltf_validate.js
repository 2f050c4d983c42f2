// tests/browser/gltf_validate.js -- the Khronos glTF validator (npm
// gltf-validator) on one .glb; prints its counts and first messages as
// JSON. Usage: node gltf_validate.js <file.glb>
'use strict';
const fs = require('fs');
const validator = require('gltf-validator');

const bytes = new Uint8Array(fs.readFileSync(process.argv[2]));
validator.validateBytes(bytes, { maxIssues: 50 }).then((report) => {
  const i = report.issues;
  console.log(JSON.stringify({
    errors: i.numErrors, warnings: i.numWarnings, infos: i.numInfos, hints: i.numHints,
    messages: i.messages.slice(0, 10).map((m) => m.code + ' ' + m.pointer + ': ' + m.message),
  }));
}).catch((e) => { console.error('gltf_validate: ' + e); process.exit(1); });
