// Validate a glTF/GLB file with Khronos' glTF validator; print its report as JSON.
// Usage: node tests/validate_gltf.js MODEL.glb  (the validator is found on NODE_PATH)
const fs = require("fs");
const validator = require("gltf-validator");

const bytes = new Uint8Array(fs.readFileSync(process.argv[2]));
validator
  .validateBytes(bytes)
  .then((report) => console.log(JSON.stringify(report)))
  .catch((error) => {
    console.error(String(error));
    process.exit(1);
  });
