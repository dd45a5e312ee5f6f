// Runs the Khronos glTF validator (npm gltf-validator) on one .gltf with its external files;
// prints the report as JSON. Usage: node gltf_validate.js VALIDATOR_DIR FILE.gltf
const fs = require("fs");
const path = require("path");
const validator = require(path.resolve(process.argv[2]));
const file = path.resolve(process.argv[3]);

validator
  .validateBytes(new Uint8Array(fs.readFileSync(file)), {
    uri: path.basename(file),
    format: "gltf",
    maxIssues: 100,
    externalResourceFunction: (uri) =>
      new Promise((resolve, reject) => {
        fs.readFile(path.resolve(path.dirname(file), decodeURIComponent(uri)), (err, data) =>
          err ? reject(err.toString()) : resolve(data)
        );
      }),
  })
  .then((report) => console.log(JSON.stringify(report)))
  .catch((error) => {
    console.error(String(error));
    process.exit(2);
  });
