"""Decodes every message of a slipfront MCAP log with the official Python readers (`mcap` and
`mcap-protobuf-support`), an independent judge of what slipfront writes, and prints a JSON
summary: messages per topic, schema per topic, and a few decoded values.

usage: python3 read_mcap.py LOG.mcap
Exit 3 if the readers are missing (the caller skips), 1 on any decoding failure.
"""

import json
import sys

try:
    from mcap.reader import make_reader
    from mcap_protobuf.decoder import DecoderFactory
except ImportError:
    print("mcap / mcap-protobuf-support are not installed", file=sys.stderr)
    sys.exit(3)


def main() -> None:
    counts: dict[str, int] = {}
    schemas: dict[str, str] = {}
    totals: list[list[float]] = []
    segments: dict[int, list[float]] = {}
    events: list[list[float]] = []
    with open(sys.argv[1], "rb") as f:
        reader = make_reader(f, decoder_factories=[DecoderFactory()])
        summary = reader.get_summary()
        for schema, channel, message, decoded in reader.iter_decoded_messages(log_time_order=False):
            counts[channel.topic] = counts.get(channel.topic, 0) + 1
            schemas[channel.topic] = schema.name
            if channel.topic == "/contact/totals":
                totals.append([decoded.step, decoded.time, decoded.friction_force, decoded.base_u_x, message.log_time])
            elif channel.topic == "/contact/segments":
                segments[decoded.step] = list(decoded.traction_t)
            elif channel.topic == "/events":
                events.append([decoded.segment, decoded.onset, decoded.slip])
    print(json.dumps({
        "chunk_indexes": len(summary.chunk_indexes) if summary else 0,
        "counts": counts,
        "schemas": schemas,
        "totals": totals,
        "segments": {str(k): v for k, v in segments.items()},
        "events": events,
    }))


if __name__ == "__main__":
    main()
