// Validates glTF files with the Khronos glTF validator (npm package gltf-validator):
//   node validate_gltf.js MODULE_DIR FILE...
// Prints each file's counts of errors, warnings, infos and hints, and every error's message;
// exits 1 when a file has errors, 2 on a usage or I/O problem.
'use strict';
const fs = require('fs');
const path = require('path');

async function main() {
  const [moduleDir, ...files] = process.argv.slice(2);
  if (!moduleDir || files.length === 0) {
    console.error('usage: node validate_gltf.js MODULE_DIR FILE...');
    return 2;
  }
  const validator = require(path.join(moduleDir, 'gltf-validator'));
  let failed = 0;
  for (const file of files) {
    const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(file)));
    const issues = report.issues;
    console.log(`${file}: ${issues.numErrors} errors, ${issues.numWarnings} warnings, ` +
                `${issues.numInfos} infos, ${issues.numHints} hints (validator ${report.validatorVersion})`);
    for (const message of issues.messages) {
      if (message.severity <= 1)
        console.log(`  ${message.severity === 0 ? 'error' : 'warning'} ${message.code} ` +
                    `${message.pointer || ''}: ${message.message}`);
    }
    if (issues.numErrors > 0) failed++;
  }
  return failed ? 1 : 0;
}

main().then((code) => process.exit(code), (error) => {
  console.error(String(error));
  process.exit(2);
});
