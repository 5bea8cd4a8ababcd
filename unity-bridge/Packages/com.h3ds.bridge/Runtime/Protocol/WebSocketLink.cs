// One websocket connection to the studio over System.Net.WebSockets.ClientWebSocket (part of .NET in
// Unity 2021+ and on Android/Quest; no plugin). Network I/O runs on the thread pool; received text
// frames and the close are queued, and the owner drains them on its own thread (Unity's main thread)
// with TryReceive, so no Unity API is ever touched off the main thread.
using System;
using System.Collections.Concurrent;
using System.IO;
using System.Net.WebSockets;
using System.Text;
using System.Threading;
using System.Threading.Tasks;

namespace H3ds.Bridge.Protocol
{
    public sealed class WebSocketLink : IDisposable
    {
        readonly ClientWebSocket _socket = new ClientWebSocket();
        readonly CancellationTokenSource _cancel = new CancellationTokenSource();
        readonly ConcurrentQueue<string> _inbox = new ConcurrentQueue<string>();
        readonly ConcurrentQueue<string> _outbox = new ConcurrentQueue<string>();
        readonly SemaphoreSlim _outSignal = new SemaphoreSlim(0);
        readonly int _maxFrameBytes;
        volatile bool _open;
        volatile string _closeReason;

        public bool IsOpen { get { return _open; } }
        /// <summary>Why the connection ended (null while it is open or connecting).</summary>
        public string CloseReason { get { return _closeReason; } }

        public WebSocketLink(int maxFrameBytes = 4 * 1024 * 1024)
        {
            _maxFrameBytes = maxFrameBytes;
            _socket.Options.KeepAliveInterval = TimeSpan.FromSeconds(15);
        }

        /// <summary>Connects, then reads and writes in the background until closed.</summary>
        public async Task ConnectAsync(Uri uri, TimeSpan timeout)
        {
            using (var connectCancel = CancellationTokenSource.CreateLinkedTokenSource(_cancel.Token))
            {
                connectCancel.CancelAfter(timeout);
                try
                {
                    await _socket.ConnectAsync(uri, connectCancel.Token).ConfigureAwait(false);
                }
                catch (Exception e)
                {
                    _closeReason = "could not connect to " + uri + ": " + e.Message;
                    throw;
                }
            }
            _open = true;
            _ = Task.Run(ReadLoop);
            _ = Task.Run(WriteLoop);
        }

        public void Send(string text)
        {
            if (!_open) return;
            _outbox.Enqueue(text);
            _outSignal.Release();
        }

        public bool TryReceive(out string text) { return _inbox.TryDequeue(out text); }

        async Task ReadLoop()
        {
            var buffer = new byte[16 * 1024];
            var frame = new MemoryStream();
            try
            {
                while (_socket.State == WebSocketState.Open)
                {
                    var r = await _socket.ReceiveAsync(new ArraySegment<byte>(buffer), _cancel.Token).ConfigureAwait(false);
                    if (r.MessageType == WebSocketMessageType.Close)
                    {
                        End("closed by the studio (" + r.CloseStatus + " " + r.CloseStatusDescription + ")");
                        return;
                    }
                    frame.Write(buffer, 0, r.Count);
                    if (frame.Length > _maxFrameBytes) { End("a message from the studio is larger than " + _maxFrameBytes + " bytes"); return; }
                    if (!r.EndOfMessage) continue;
                    if (r.MessageType == WebSocketMessageType.Text) _inbox.Enqueue(Encoding.UTF8.GetString(frame.GetBuffer(), 0, (int)frame.Length));
                    frame.SetLength(0);
                }
                End("connection " + _socket.State);
            }
            catch (Exception e) { End("connection lost: " + e.Message); }
        }

        async Task WriteLoop()
        {
            try
            {
                while (_open)
                {
                    await _outSignal.WaitAsync(_cancel.Token).ConfigureAwait(false);
                    string text;
                    while (_open && _outbox.TryDequeue(out text))
                    {
                        var bytes = Encoding.UTF8.GetBytes(text);
                        await _socket.SendAsync(new ArraySegment<byte>(bytes), WebSocketMessageType.Text, true, _cancel.Token).ConfigureAwait(false);
                    }
                }
            }
            catch (Exception e) { End("send failed: " + e.Message); }
        }

        void End(string reason)
        {
            if (_closeReason == null) _closeReason = reason;
            _open = false;
            _outSignal.Release();
        }

        /// <summary>Closes politely (1000) if open; pending sends are dropped (the Outbox keeps what matters).</summary>
        public void Close(string reason)
        {
            if (_open && _socket.State == WebSocketState.Open)
            {
                try { _socket.CloseOutputAsync(WebSocketCloseStatus.NormalClosure, reason, CancellationToken.None).Wait(1000); }
                catch (Exception) { }
            }
            End(reason);
        }

        public void Dispose()
        {
            End("disposed");
            _cancel.Cancel();
            _socket.Dispose();
        }
    }
}
