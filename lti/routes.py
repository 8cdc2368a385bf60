"""The tool's routes, served by the app itself (serve.py puts ``LtiRoutes`` in front of Streamlit):

    /lti/login        OIDC third-party login initiation (GET or POST)
    /lti/launch       the platform's form post: a launch (student, instructor) or a deep-linking request
    /lti/deep_link    the instructor's choice in the "add external tool" dialog, answered to the LMS
    /lti/jwks         the tool's public key (the platform checks the tool's signed messages with it)
    /lti/config.json  a Canvas-style JSON configuration (paste its URL into Canvas's developer key)

Each handler runs in a worker thread (the platform's JWKS and the database are blocking calls).
"""
from __future__ import annotations

import datetime as dt
import html
import time
import uuid
from urllib.parse import quote

import jwt
from starlette.concurrency import run_in_threadpool
from starlette.requests import Request
from starlette.responses import HTMLResponse, JSONResponse, RedirectResponse, Response
from starlette.routing import Route, Router

from assignments import records, signing
from lti import launch as lti, platforms, store
from lti.launch import DL_CLAIM, Launch, Refused

TITLE = "Dynamics Lab"
AUTO_SUBMIT = "document.forms[0].submit()"  # allowed by its hash in edge/headers.py's policy
PAGE = """<!doctype html><html lang="en"><head><meta charset="utf-8"><meta name="viewport" content="width=device-width,initial-scale=1">
<title>{title}</title><style>body{{font-family:system-ui,sans-serif;max-width:40rem;margin:1.5rem auto;padding:0 1rem;line-height:1.5}}
label{{display:block;margin:.6rem 0 .2rem;font-weight:600}} input,select{{font-size:1rem;padding:.3rem;max-width:100%;box-sizing:border-box}} .answers label{{font-weight:400;display:block;margin:.2rem 0}}
button{{font-size:1rem;padding:.5rem 1rem;margin-top:1rem}} .refused{{border-left:4px solid #b3261e;padding-left:.8rem}}</style></head>
<body>{body}</body></html>"""


def page(title: str, body: str, status: int = 200) -> HTMLResponse:
    return HTMLResponse(PAGE.format(title=html.escape(title), body=body), status_code=status)


def refusal(error: Refused) -> HTMLResponse:
    return page("Not accepted", f"<h1>Not accepted</h1><p class='refused'>{html.escape(str(error))}</p>", 400)


async def _params(request: Request) -> dict:
    params = dict(request.query_params)
    if request.method == "POST":
        params.update({k: v for k, v in (await request.form()).items() if isinstance(v, str)})
    return params


async def login(request: Request) -> Response:
    params = await _params(request)
    try:
        return RedirectResponse(await run_in_threadpool(lti.login_redirect, params), status_code=302)
    except Refused as error:
        return refusal(error)


def _after_launch(form: dict) -> Response:
    checked = lti.verify(form, store.spender())
    if checked.staff and not checked.context.get("id"):  # staff see a course's assignments: which course?
        raise lti.refuse(f"staff launch without a context from {checked.platform.issuer}",
                         "Open Dynamics Lab from a course in the LMS: its instructors see that course's work.")
    if checked.message == "LtiDeepLinkingRequest":
        return _picker(checked)
    context = checked.context.get("id", "")
    assignment = store.assignment_of(checked)
    base = platforms.public_url()
    if checked.staff:
        roster = (checked.claims.get(lti.NRPS_CLAIM) or {}).get("context_memberships_url", "")
        token = lti.handoff({"role": "instructor", "iss": checked.platform.issuer, "aud": checked.platform.client_id,
                             "ctx": context,
                             "title": str(checked.context.get("title", ""))[:120], "a": assignment, "nrps": roster})
        return RedirectResponse(f"{base}/assignments?lti={quote(token)}", status_code=303)
    if assignment is None:
        raise store.refuse_unplaced(checked)
    identity = store.student(checked, assignment)
    settings = records.assignment(assignment)
    token = lti.handoff({"role": "student", "a": identity.assignment_id, "l": identity.label, "s": identity.seed})
    return RedirectResponse(f"{base}/{settings.problem}?lti={quote(token)}", status_code=303)


async def launch(request: Request) -> Response:
    form = await _params(request)
    try:
        return await run_in_threadpool(_after_launch, form)
    except Refused as error:
        return refusal(error)
    except records.RecordingUnavailable as error:
        return page("Not available", f"<h1>Not available now</h1><p class='refused'>{html.escape(str(error))}</p>", 503)


# -- deep linking: the instructor's choice in the LMS's dialog

DL_SECONDS = 1800


def _picker(checked: Launch, problem: str = "", said: str = "") -> Response:
    from solvers.catalog import BY_ID, PROBLEMS

    if not checked.staff:
        raise lti.refuse("deep-linking request from a non-staff role",
                         "Only the course's instructors can add Dynamics Lab activities.")
    settings = checked.claims.get(DL_CLAIM + "deep_linking_settings") or {}
    if not settings.get("deep_link_return_url"):
        raise lti.refuse("deep-linking request without deep_link_return_url")
    if not platforms.owns(checked.platform, settings["deep_link_return_url"]):
        raise lti.refuse(f"deep_link_return_url {str(settings['deep_link_return_url'])[:200]!r} is not on "
                         f"{checked.platform.issuer}'s registered origins")
    kept = {lti.CLAIM + "deployment_id": checked.deployment, lti.CLAIM + "roles": checked.claim("roles"),
            lti.CLAIM + "context": {k: checked.context[k] for k in ("id", "title") if k in checked.context},
            DL_CLAIM + "deep_linking_settings": {k: settings[k] for k in ("deep_link_return_url", "data")
                                                 if k in settings}}  # what the answer needs, no more
    sealed = signing.seal("lti-deep-link", {"iss": checked.platform.issuer, "aud": checked.platform.client_id,
                                            "claims": kept}, DL_SECONDS)
    hidden = f"<input type='hidden' name='dl' value='{html.escape(sealed)}'>"
    notice = f"<p class='refused'>{html.escape(said)}</p>" if said else ""
    if problem not in BY_ID:
        options = "".join(f"<option value='{p.id}'>{html.escape(p.title)}</option>" for p in PROBLEMS)
        return page("Add an assignment", f"<h1>Add a Dynamics Lab assignment</h1>{notice}<form method='post' "
                    f"action='/lti/deep_link'>{hidden}<label for='problem'>Problem</label><select id='problem' "
                    f"name='problem'>{options}</select><br><button type='submit'>Next</button></form>")
    chosen = BY_ID[problem]
    answers = chosen.answers_of(chosen.solver.solve())
    boxes = "".join(f"<label><input type='checkbox' name='answer' value='{a.name}' checked> "
                    f"{html.escape(a.heading)}</label>" for a in answers)
    boxes += (f"<label><input type='checkbox' name='answer' value='{records.DIAGRAM}'> "
              f"{html.escape(records.DIAGRAM_HEADING)} (drawn on the page)</label>")
    due = (dt.datetime.now(dt.timezone.utc) + dt.timedelta(days=7)).strftime("%Y-%m-%dT%H:%M")
    return page("Add an assignment", f"""<h1>Add “{html.escape(chosen.title)}”</h1>{notice}
<form method='post' action='/lti/deep_link'>{hidden}<input type='hidden' name='problem' value='{problem}'>
<label for='title'>Title</label><input id='title' name='title' maxlength='120' size='40' value='{html.escape(chosen.title)}' required>
<fieldset class='answers'><legend>Answers that count</legend>{boxes}</fieldset>
<label for='tolerance'>Tolerance (relative, e.g. 0.005 for 0.5 %)</label><input id='tolerance' name='tolerance' value='0.005' inputmode='decimal'>
<label for='attempts'>Attempts per answer</label><input id='attempts' name='attempts' value='3' inputmode='numeric'>
<label for='due'>Due (UTC)</label><input id='due' name='due' type='datetime-local' value='{due}'>
<input type='hidden' name='step' value='create'><br><button type='submit'>Add to the course</button></form>""")


def _chosen(form: dict, answers: list[str]) -> records.Settings:
    try:
        tolerance, attempts = float(form.get("tolerance", "")), int(form.get("attempts", ""))
        due = dt.datetime.fromisoformat(form.get("due", "")).replace(tzinfo=dt.timezone.utc)
    except ValueError:
        raise ValueError("The tolerance must be a number, the attempts a whole number, and the due time a date "
                         "and time.") from None
    if not answers:
        raise ValueError("Choose at least one answer that counts.")
    return records.Settings.of(form.get("title", "").strip()[:120], form.get("problem", ""), answers, tolerance, due,
                               attempts)


def _deep_link(form: dict, answers: list[str]) -> Response:
    sealed = signing.unseal("lti-deep-link", form.get("dl"))
    if sealed is None:
        raise lti.refuse("deep-link choice with an altered or expired seal",
                         "This dialog was open too long or was altered; close it and add the activity again.")
    checked = Launch(platforms.find(sealed["iss"], sealed["aud"]), sealed["claims"] | {"aud": sealed["aud"]})
    if checked.platform is None:
        raise lti.refuse(f"deep-link choice for a platform no longer registered: {sealed['iss']}")
    if form.get("step") != "create":
        return _picker(checked, form.get("problem", ""))
    try:
        settings = _chosen(form, answers)
        made = records.create(settings)
    except ValueError as error:
        return _picker(checked, form.get("problem", ""), str(error))
    context = checked.context.get("id", "")
    placed = store.contexts_of(made.id)
    elsewhere = [c for c in placed if c != (checked.platform.issuer, context)]
    if elsewhere or (not made.new and (checked.platform.issuer, context) not in placed
                     and records.roster(made.id)):  # not another course's, nor a signed-link class's
        return _picker(checked, form.get("problem", ""), "An assignment with this title, problem and due time exists in "
                                                 "another course; give this one another title.")
    return _deep_link_answer(checked, made.id, settings)


def _deep_link_answer(checked: Launch, assignment_id: int, settings: records.Settings) -> Response:
    dl = checked.claims[DL_CLAIM + "deep_linking_settings"]
    item = {"type": "ltiResourceLink", "title": settings.title, "url": platforms.public_url() + "/lti/launch",
            "custom": {"dl_assignment": store.placement(checked, assignment_id)},
            "lineItem": {"scoreMaximum": settings.out_of, "label": settings.title, "resourceId": str(assignment_id)},
            "submission": {"endDateTime": settings.due.isoformat()}}
    now = int(time.time())
    claims = {"iss": checked.platform.client_id, "aud": checked.platform.issuer, "iat": now, "exp": now + 600,
              "nonce": uuid.uuid4().hex, lti.CLAIM + "message_type": "LtiDeepLinkingResponse",
              lti.CLAIM + "version": "1.3.0", lti.CLAIM + "deployment_id": checked.deployment,
              DL_CLAIM + "content_items": [item]}
    if dl.get("data"):
        claims[DL_CLAIM + "data"] = dl["data"]
    token = jwt.encode(claims, platforms.tool_key(), algorithm="RS256", headers={"kid": platforms.tool_jwk()["kid"]})
    return page("Adding to your course", f"""<h1>“{html.escape(settings.title)}” is ready</h1>
<form method='post' action='{html.escape(dl["deep_link_return_url"])}'><input type='hidden' name='JWT' value='{token}'>
<button type='submit'>Return to the course</button></form><script>{AUTO_SUBMIT}</script>""")


async def deep_link(request: Request) -> Response:
    form = await request.form()
    fields = {k: v for k, v in form.items() if isinstance(v, str)}
    answers = [a for a in form.getlist("answer") if isinstance(a, str)]
    try:
        return await run_in_threadpool(_deep_link, fields, answers)
    except Refused as error:
        return refusal(error)
    except records.RecordingUnavailable as error:
        return page("Not available", f"<h1>Not available now</h1><p class='refused'>{html.escape(str(error))}</p>", 503)


async def jwks(request: Request) -> Response:
    return JSONResponse({"keys": [platforms.tool_jwk()]})


async def config(request: Request) -> Response:
    """Canvas's JSON configuration for a developer key (LTI Key, "Enter URL")."""
    base = platforms.public_url()
    return JSONResponse({
        "title": TITLE, "description": "Rigid-body dynamics problems, each student with their own givens; "
        "graded attempts sent back to the gradebook.", "oidc_initiation_url": base + "/lti/login",
        "target_link_uri": base + "/lti/launch", "public_jwk_url": base + "/lti/jwks",
        "scopes": ["https://purl.imsglobal.org/spec/lti-ags/scope/lineitem",
                   "https://purl.imsglobal.org/spec/lti-ags/scope/score",
                   "https://purl.imsglobal.org/spec/lti-nrps/scope/contextmembership.readonly"],
        "extensions": [{"platform": "canvas.instructure.com", "privacy_level": "anonymous", "settings": {
            "placements": [{"placement": "assignment_selection", "message_type": "LtiDeepLinkingRequest",
                            "target_link_uri": base + "/lti/launch"},
                           {"placement": "link_selection", "message_type": "LtiDeepLinkingRequest",
                            "target_link_uri": base + "/lti/launch"}]}}],
        "custom_fields": {}})


ROUTES = [Route("/lti/login", login, methods=["GET", "POST"]), Route("/lti/launch", launch, methods=["POST"]),
          Route("/lti/deep_link", deep_link, methods=["POST"]), Route("/lti/jwks", jwks, methods=["GET"]),
          Route("/lti/config.json", config, methods=["GET"])]


class LtiRoutes:
    """ASGI middleware: ``/lti/…`` answered here when LTI is on; everything else goes to Streamlit."""

    def __init__(self, app):
        from edge import base_path

        self.app = app
        self.router = Router(ROUTES)
        self.prefix = base_path()  # under a path prefix, DL_PUBLIC_URL ends with it too

    async def __call__(self, scope, receive, send):
        if (scope["type"] == "http" and scope["path"].startswith(self.prefix + "/lti/")
                and platforms.enabled()):
            body = await _bounded(receive)
            if body is None:  # read no further than the bound: an oversize post costs nobody memory
                return await page("Too large", "<h1>Not accepted</h1><p class='refused'>This request is larger "
                                  "than any launch from a course site.</p>", 413)(scope, receive, send)
            replay = iter([{"type": "http.request", "body": body, "more_body": False}])
            return await self.router({**scope, "path": scope["path"][len(self.prefix):]},
                                     lambda: _next(replay, receive), send)
        return await self.app(scope, receive, send)


MAX_BODY = 256 * 1024  # an id_token with every claim is a few kB; Canvas's largest launches stay far below


async def _bounded(receive) -> bytes | None:
    """The request's body, or None once it passes MAX_BODY (whatever Content-Length says)."""
    chunks, size = [], 0
    while True:
        message = await receive()
        if message["type"] != "http.request":
            return b"".join(chunks)
        size += len(message.get("body", b""))
        if size > MAX_BODY:
            return None
        chunks.append(message.get("body", b""))
        if not message.get("more_body", False):
            return b"".join(chunks)


async def _next(replay, receive):
    message = next(replay, None)
    return message if message is not None else await receive()
