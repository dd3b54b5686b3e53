#!/usr/bin/env python3
"""A fake OpenAI-compatible chat-completions server for pipeline_templates_test
(standard library only). Usage: pipeline_templates_fake_vlm.py MODE
  ok       checks the request's shape and answers a canned completion
  garbage  answers 200 with text that is not the JSON asked for
  error    answers HTTP 500
Binds a free loopback port, prints "PORT" on the first line, serves until
killed (or 60 s without a request). A request of the wrong shape gets HTTP 400
with the reason, so the test sees it as a failed call."""
import base64
import json
import sys
from http.server import BaseHTTPRequestHandler, HTTPServer

MODE = sys.argv[1] if len(sys.argv) > 1 else "ok"
ANSWER = ('Here you go:\n```json\n{"effect": "illumination", "mapping": "cumulative", '
          '"reasons": "the magenta part lights up a little more at each press"}\n```')


def check(body):
    req = json.loads(body)
    if req.get("model") != "test-model":
        return "model is not test-model"
    msgs = req.get("messages")
    if not isinstance(msgs, list) or not msgs:
        return "no messages"
    content = msgs[0].get("content")
    if msgs[0].get("role") != "user" or not isinstance(content, list):
        return "first message is not a user message with a content list"
    texts = [c for c in content if c.get("type") == "text"]
    images = [c for c in content if c.get("type") == "image_url"]
    if len(texts) != 1 or "JSON" not in texts[0].get("text", ""):
        return "no prompt asking for JSON"
    if not 2 <= len(images) <= 4:
        return "%d images, expected 2-4" % len(images)
    for im in images:
        url = im.get("image_url", {}).get("url", "")
        prefix = "data:image/png;base64,"
        if not url.startswith(prefix):
            return "image is not a PNG data URL"
        data = base64.b64decode(url[len(prefix):], validate=True)
        if not data.startswith(b"\x89PNG\r\n\x1a\n"):
            return "image does not decode to a PNG"
    return None


class Handler(BaseHTTPRequestHandler):
    def log_message(self, *args):
        pass

    def reply(self, code, text):
        data = text.encode()
        self.send_response(code)
        self.send_header("Content-Type", "application/json")
        self.send_header("Content-Length", str(len(data)))
        self.end_headers()
        self.wfile.write(data)

    def do_POST(self):
        body = self.rfile.read(int(self.headers.get("Content-Length", 0)))
        if self.path.rstrip("/") != "/v1/chat/completions":
            return self.reply(404, '{"error": "no such path"}')
        if MODE == "error":
            return self.reply(500, '{"error": "internal"}')
        try:
            problem = check(body)
        except Exception as e:  # noqa: BLE001 - any malformed request is a 400
            problem = "request does not parse: %s" % e
        if problem:
            return self.reply(400, json.dumps({"error": problem}))
        content = "I think it glows, probably." if MODE == "garbage" else ANSWER
        self.reply(200, json.dumps({"id": "x", "object": "chat.completion", "model": "test-model",
                                    "choices": [{"index": 0, "finish_reason": "stop",
                                                 "message": {"role": "assistant", "content": content}}]}))


class Server(HTTPServer):
    def handle_timeout(self):
        sys.exit(0)  # nobody asked for a minute: the test is gone


def main():
    server = Server(("127.0.0.1", 0), Handler)
    server.timeout = 60
    print(server.server_address[1], flush=True)
    while True:
        server.handle_request()


if __name__ == "__main__":
    main()
