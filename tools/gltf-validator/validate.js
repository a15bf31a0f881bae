#!/usr/bin/env node
// Validates glTF files with the Khronos glTF-Validator (the npm package has no command line).
//   node tools/gltf-validator/validate.js FILE.glb|FILE.gltf ...
// Prints every error and warning (infos and hints as counts); exits 1 if any file has an error or a
// warning, 2 if a file cannot be read or the validator is not installed.
'use strict';
const fs = require('fs');
const path = require('path');

let validator;
try {
  validator = require('gltf-validator');
} catch (e) {
  console.error('gltf-validator is not installed: run `npm ci --prefix ' + __dirname + '`');
  process.exit(2);
}

async function validate(file) {
  const bytes = new Uint8Array(fs.readFileSync(file));
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 0,
    externalResourceFunction: (uri) => new Promise((resolve, reject) => {
      fs.readFile(path.resolve(path.dirname(file), decodeURIComponent(uri)), (err, data) => {
        if (err) reject(err); else resolve(new Uint8Array(data));
      });
    }),
  });
  const issues = report.issues;
  for (const m of issues.messages) {
    if (m.severity > 1) continue;  // 0 error, 1 warning, 2 info, 3 hint
    console.log(`${file}: ${m.severity === 0 ? 'error' : 'warning'} ${m.code} ${m.pointer || ''}: ${m.message}`);
  }
  console.log(`${file}: ${issues.numErrors} errors, ${issues.numWarnings} warnings, ${issues.numInfos} infos, ` +
              `${issues.numHints} hints`);
  return issues.numErrors + issues.numWarnings;
}

(async () => {
  const files = process.argv.slice(2);
  if (files.length === 0) {
    console.error('usage: node validate.js FILE.glb|FILE.gltf ...');
    process.exit(2);
  }
  let bad = 0;
  for (const f of files) {
    try {
      bad += await validate(f);
    } catch (e) {
      console.error(`${f}: cannot validate: ${e.message || e}`);
      process.exit(2);
    }
  }
  process.exit(bad > 0 ? 1 : 0);
})();
