/** An error the user caused (bad flag, unknown scene, unavailable backend): printed as one line, exit code 2. */
export class UsageError extends Error {}
