// Validates signal manifests with ajv at its defaults (the Ajv class: draft-07, strict mode), as a user of the
// schema would: node validate_manifests.mjs SCHEMA FILE...
// Prints, tab-separated, one WARN line per message ajv logs while compiling the schema (strict mode's
// complaints, which a clean schema has none of), then per file `OK file` or `ERR file count errors-as-JSON`.
import Ajv from "ajv";
import { readFileSync } from "node:fs";

const [schemaFile, ...files] = process.argv.slice(2);
const logged = [];
const keep = (...parts) => logged.push(parts.join(" ").replace(/\s+/g, " "));
// Only where ajv's messages go is changed, not what it checks.
const ajv = new Ajv({ logger: { log: keep, warn: keep, error: keep } });
const validate = ajv.compile(JSON.parse(readFileSync(schemaFile, "utf8")));
for (const message of logged) console.log(`WARN\t${message}`);
for (const file of files) {
  let manifest;
  try {
    manifest = JSON.parse(readFileSync(file, "utf8"));
  } catch (error) {
    console.log(`ERR\t${file}\t1\t${JSON.stringify([{ message: String(error) }])}`);
    continue;
  }
  if (validate(manifest)) console.log(`OK\t${file}`);
  else console.log(`ERR\t${file}\t${validate.errors.length}\t${JSON.stringify(validate.errors)}`);
}
