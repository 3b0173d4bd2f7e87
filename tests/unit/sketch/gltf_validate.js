// Validates glTF files with the Khronos glTF validator (npm package gltf-validator): prints the
// issues of each file and exits 1 when any file has an error.
// Use: NODE_PATH=<node_modules with gltf-validator> node gltf_validate.js FILE...
const validator = require('gltf-validator');
const fs = require('fs');

(async () => {
  let errors = 0;
  for (const file of process.argv.slice(2)) {
    const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(file)));
    const issues = report.issues;
    console.log(`${file}: ${issues.numErrors} errors, ${issues.numWarnings} warnings, ${issues.numInfos} infos`);
    for (const m of issues.messages.slice(0, 20)) console.log(`  [${m.severity}] ${m.code}: ${m.message} ${m.pointer || ''}`);
    errors += issues.numErrors;
  }
  process.exit(errors > 0 ? 1 : 0);
})().catch((e) => {
  console.error(e);
  process.exit(1);
});
